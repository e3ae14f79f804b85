/* History fix of pair_style mdrdem; see fix_mdrdem_history.h. The history values themselves are
   opaque here: only the Rust library reads them (crates/mdr-lammps/src/history.rs gives the
   layout and the sign of each value seen from the partner atom). */
#include "fix_mdrdem_history.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "memory.h"
#include "neigh_list.h"
#include "pair.h"
#include "utils.h"

#include "mdrdem.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

enum { NPARTNER, PERPARTNER };

FixMdrdemHistory::FixMdrdemHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), drop_history(false), partners_current(true),
    npartner(nullptr), poffset(nullptr), maxpartner(0), nlocal_neigh(0), nall_neigh(0),
    have_neigh(false), commflag(NPARTNER)
{
  if (narg != 4) error->all(FLERR, "Illegal fix MDRDEM/HISTORY command: ID group MDRDEM/HISTORY dnum");
  dnum = utils::inumeric(FLERR, arg[3], false, lmp);
  if (dnum < 1 || dnum > 10) error->all(FLERR, "fix MDRDEM/HISTORY: dnum must be in 1..10");
  mdrdem_partner_signs(signs);

  restart_peratom = 1;
  restart_global = 1;    // so that write_restart() syncs the partner lists first
  create_attribute = 1;
  maxexchange_dynamic = 1;
  newton_pair = force->newton_pair;
  if (newton_pair) comm_reverse = 1;    // partner counts of ghost atoms

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixMdrdemHistory::~FixMdrdemHistory()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(npartner);
  memory->sfree(poffset);
}

int FixMdrdemHistory::setmask()
{
  return PRE_EXCHANGE | MIN_PRE_EXCHANGE | POST_NEIGHBOR | MIN_POST_NEIGHBOR | POST_RUN;
}

void FixMdrdemHistory::init()
{
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style mdrdem requires atoms with IDs");
  if (force->newton_pair != newton_pair)
    error->all(FLERR, "pair_style mdrdem: newton_pair changed after the history was created");
  for (auto &ifix : modify->get_fix_list()) {
    if (ifix == this) break;
    if (ifix->pre_exchange_migrate)
      error->all(FLERR, "fix MDRDEM/HISTORY comes after fix {} which migrates atoms in pre_exchange",
                 ifix->id);
  }
}

int FixMdrdemHistory::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "drop_history") == 0) {
    if (narg < 2) error->all(FLERR, "fix_modify drop_history needs yes or no");
    drop_history = utils::logical(FLERR, arg[1], false, lmp) == 1;
    return 2;
  }
  return 0;
}

void FixMdrdemHistory::setup_post_neighbor()
{
  post_neighbor();
}

int64_t FixMdrdemHistory::reserve(int i, int n)
{
  auto start = (int64_t) partner_tag.size();
  poffset[i] = start;
  partner_tag.resize(start + n);
  partner_values.resize((start + n) * dnum);
  return start;
}

/* Copy the histories of the current neighbour list into per-atom partner lists (both atoms of
   a pair get an entry, the partner's seen with the partner signs). With newton on, entries of
   ghost atoms are sent to their owners (reverse communication). */
void FixMdrdemHistory::collect_partners()
{
  if (!have_neigh || pair == nullptr || pair->list == nullptr) return;
  NeighList *list = pair->list;
  tagint *tag = atom->tag;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  const int counted = newton_pair ? nall_neigh : nlocal_neigh;

  // Test hook (fix_modify MDRDEM_HISTORY drop_history yes): every exchange forgets every
  // contact's history, as a style without a history fix would. Tests use it to show that
  // their comparison detects lost histories.
  if (drop_history) touch.assign(touch.size(), 0);

  partner_tag.clear();
  partner_values.clear();
  for (int i = 0; i < counted; i++) npartner[i] = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    const int64_t base = neigh_offset[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      if (!touch[base + jj]) continue;
      npartner[i]++;
      const int j = jlist[jj] & NEIGHMASK;
      if (j < counted) npartner[j]++;
    }
  }
  if (newton_pair) {
    commflag = NPARTNER;
    comm->reverse_comm(this);
  }
  for (int i = 0; i < counted; i++) reserve(i, npartner[i]);
  for (int i = 0; i < counted; i++) npartner[i] = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    const int64_t base = neigh_offset[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      if (!touch[base + jj]) continue;
      const double *one = &values[(base + jj) * dnum];
      const int j = jlist[jj] & NEIGHMASK;
      int64_t m = poffset[i] + npartner[i]++;
      partner_tag[m] = tag[j];
      std::memcpy(&partner_values[m * dnum], one, dnum * sizeof(double));
      if (j < counted) {
        m = poffset[j] + npartner[j]++;
        partner_tag[m] = tag[i];
        for (int n = 0; n < dnum; n++) partner_values[m * dnum + n] = signs[n] * one[n];
      }
    }
  }
  if (newton_pair) {
    commflag = PERPARTNER;
    comm->reverse_comm_variable(this);
  }
  maxpartner = 0;
  for (int i = 0; i < nlocal_neigh; i++) maxpartner = std::max(maxpartner, npartner[i]);
  maxexchange = (dnum + 1) * maxpartner + 1;
  for (int i = nlocal_neigh; i < atom->nlocal; i++) npartner[i] = 0;
  partners_current = true;
}

void FixMdrdemHistory::pre_exchange()
{
  collect_partners();
}

/* After a neighbour list is built: each neighbour gets the history found in its atom's partner
   list (by partner tag), or zeroes. */
void FixMdrdemHistory::post_neighbor()
{
  const int nlocal = atom->nlocal;
  nlocal_neigh = nlocal;
  nall_neigh = nlocal + atom->nghost;
  NeighList *list = pair->list;
  tagint *tag = atom->tag;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  if ((int) neigh_offset.size() < nall_neigh) neigh_offset.resize(nall_neigh);
  int64_t total = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    neigh_offset[i] = total;
    total += numneigh[i];
  }
  touch.assign(total, 0);
  values.assign(total * dnum, 0.0);
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    int *jlist = firstneigh[i];
    const int np = npartner[i];
    const tagint *ptag = np ? &partner_tag[poffset[i]] : nullptr;
    const int64_t base = neigh_offset[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      jlist[jj] = j;
      if (np == 0) continue;
      const tagint jtag = tag[j];
      for (int m = 0; m < np; m++) {
        if (ptag[m] == jtag) {
          touch[base + jj] = 1;
          std::memcpy(&values[(base + jj) * dnum], &partner_values[(poffset[i] + m) * dnum],
                      dnum * sizeof(double));
          break;
        }
      }
    }
  }
  have_neigh = true;
  partners_current = false;
}

void FixMdrdemHistory::write_restart(FILE *fp)
{
  // During a run (restart output) the neighbour-order histories are newer than the partner
  // lists; between runs post_run() has already collected them (and atoms may have been
  // exchanged since, so the neighbour list must not be read again).
  if (!partners_current) collect_partners();
  if (comm->me == 0) {
    int size = 0;
    fwrite(&size, sizeof(int), 1, fp);
  }
}

void FixMdrdemHistory::grow_arrays(int nmax)
{
  memory->grow(npartner, nmax, "mdrdem/history:npartner");
  poffset = (int64_t *) memory->srealloc(poffset, nmax * sizeof(int64_t), "mdrdem/history:poffset");
}

void FixMdrdemHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  npartner[j] = npartner[i];
  poffset[j] = poffset[i];
}

void FixMdrdemHistory::set_arrays(int i)
{
  npartner[i] = 0;
  poffset[i] = 0;
}

int FixMdrdemHistory::pack_exchange(int i, double *buf)
{
  int m = 0;
  buf[m++] = npartner[i];
  for (int n = 0; n < npartner[i]; n++) {
    buf[m++] = ubuf(partner_tag[poffset[i] + n]).d;
    std::memcpy(&buf[m], &partner_values[(poffset[i] + n) * dnum], dnum * sizeof(double));
    m += dnum;
  }
  return m;
}

int FixMdrdemHistory::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  npartner[nlocal] = static_cast<int>(buf[m++]);
  maxpartner = std::max(maxpartner, npartner[nlocal]);
  int64_t start = reserve(nlocal, npartner[nlocal]);
  for (int n = 0; n < npartner[nlocal]; n++) {
    partner_tag[start + n] = (tagint) ubuf(buf[m++]).i;
    std::memcpy(&partner_values[(start + n) * dnum], &buf[m], dnum * sizeof(double));
    m += dnum;
  }
  return m;
}

int FixMdrdemHistory::pack_restart(int i, double *buf)
{
  int m = 1;
  buf[m++] = npartner[i];
  for (int n = 0; n < npartner[i]; n++) {
    buf[m++] = ubuf(partner_tag[poffset[i] + n]).d;
    std::memcpy(&buf[m], &partner_values[(poffset[i] + n) * dnum], dnum * sizeof(double));
    m += dnum;
  }
  buf[0] = m;    // first value: this fix's count, as every per-atom restart fix writes it
  return m;
}

void FixMdrdemHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  npartner[nlocal] = static_cast<int>(extra[nlocal][m++]);
  maxpartner = std::max(maxpartner, npartner[nlocal]);
  int64_t start = reserve(nlocal, npartner[nlocal]);
  for (int n = 0; n < npartner[nlocal]; n++) {
    partner_tag[start + n] = (tagint) ubuf(extra[nlocal][m++]).i;
    std::memcpy(&partner_values[(start + n) * dnum], &extra[nlocal][m], dnum * sizeof(double));
    m += dnum;
  }
}

int FixMdrdemHistory::size_restart(int nlocal)
{
  return (dnum + 1) * npartner[nlocal] + 2;
}

int FixMdrdemHistory::maxsize_restart()
{
  int all = 0;
  MPI_Allreduce(&maxpartner, &all, 1, MPI_INT, MPI_MAX, world);
  return (dnum + 1) * all + 2;
}

int FixMdrdemHistory::pack_reverse_comm_size(int n, int first)
{
  int m = 0;
  for (int i = first; i < first + n; i++) m += 1 + (dnum + 1) * npartner[i];
  return m;
}

int FixMdrdemHistory::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = npartner[i];
    if (commflag == PERPARTNER) {
      for (int k = 0; k < npartner[i]; k++) {
        buf[m++] = ubuf(partner_tag[poffset[i] + k]).d;
        std::memcpy(&buf[m], &partner_values[(poffset[i] + k) * dnum], dnum * sizeof(double));
        m += dnum;
      }
    }
  }
  return m;
}

void FixMdrdemHistory::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    const int count = static_cast<int>(buf[m++]);
    if (commflag == NPARTNER) {
      npartner[j] += count;
      continue;
    }
    for (int k = 0; k < count; k++) {
      const int64_t kk = poffset[j] + npartner[j]++;
      partner_tag[kk] = (tagint) ubuf(buf[m++]).i;
      std::memcpy(&partner_values[kk * dnum], &buf[m], dnum * sizeof(double));
      m += dnum;
    }
  }
}

double FixMdrdemHistory::memory_usage()
{
  double bytes = (double) atom->nmax * (sizeof(int) + sizeof(int64_t));
  bytes += (double) partner_tag.capacity() * sizeof(tagint);
  bytes += (double) partner_values.capacity() * sizeof(double);
  bytes += (double) neigh_offset.capacity() * sizeof(int64_t);
  bytes += (double) touch.capacity() * sizeof(int) + (double) values.capacity() * sizeof(double);
  return bytes;
}
