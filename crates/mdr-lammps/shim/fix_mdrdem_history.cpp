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
#include "update.h"
#include "utils.h"

#include "mdrdem.h"

#include <algorithm>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

enum { NPARTNER, PERPARTNER };

// Per-atom record of the step a run ended on: v, omega as its force call saw them (0-5), v, omega
// at its end (6-11).
static constexpr int RECORD = 12;
// Per atom in the setup call's forward communication: the replayed v and omega, and the owner's
// current v (a ghost's velocity may carry a box-deformation offset, which is added back).
static constexpr int REPLAY_COMM = 9;
static const double NOT_KNOWN = std::numeric_limits<double>::quiet_NaN();

FixMdrdemHistory::FixMdrdemHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), replayed_step(-1), pair(nullptr), drop_history(false), drop_migrated(false), setup_update(false),
    partners_current(true),
    npartner(nullptr), poffset(nullptr), maxpartner(0), nlocal_neigh(0), nall_neigh(0),
    have_neigh(false), commflag(NPARTNER), saved_step(-1), record_step(-1), step_values_step(-1),
    record(nullptr), file_width(0)
{
  if (narg != 4) error->all(FLERR, "Illegal fix MDRDEM/HISTORY command: ID group MDRDEM/HISTORY dnum");
  dnum = utils::inumeric(FLERR, arg[3], false, lmp);
  if (mdrdem_partner_signs(dnum, signs) != 0)
    error->all(FLERR, "fix MDRDEM/HISTORY: dnum must be 5, 6, 10 or 11 (got {})", dnum);
  width = file_width = dnum;

  restart_peratom = 1;
  restart_global = 1;    // so that write_restart() syncs the partner lists first
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1 + RECORD;    // until the first partner lists are collected
  newton_pair = force->newton_pair;
  if (newton_pair) comm_reverse = 1;    // partner counts of ghost atoms
  comm_forward = REPLAY_COMM;

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
  memory->destroy(record);
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
      error->all(FLERR, "fix {} migrates atoms in pre_exchange and comes before the contact "
                 "histories of pair_style mdrdem: define pair_style mdrdem before fix {}",
                 ifix->id, ifix->id);
  }
}

int FixMdrdemHistory::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "drop_history") == 0) {
    if (narg < 2) error->all(FLERR, "fix_modify drop_history needs yes or no");
    drop_history = utils::logical(FLERR, arg[1], false, lmp) == 1;
    return 2;
  }
  // Test hook: an atom sent to another rank (an exchange, fix balance, the balance command)
  // arrives there without its partner list, as with a history kept only where the atom was.
  // The balancing tests use it to show that their comparison detects histories left behind.
  if (strcmp(arg[0], "drop_migrated") == 0) {
    if (narg < 2) error->all(FLERR, "fix_modify drop_migrated needs yes or no");
    drop_migrated = utils::logical(FLERR, arg[1], false, lmp) == 1;
    return 2;
  }
  // Test hook: the setup call of a run advances every history by one more step (with the
  // current velocities), as a style that ignores update->setupflag would. The restart test uses
  // it to show that its comparison detects such a setup call.
  if (strcmp(arg[0], "setup_update") == 0) {
    if (narg < 2) error->all(FLERR, "fix_modify setup_update needs yes or no");
    setup_update = utils::logical(FLERR, arg[1], false, lmp) == 1;
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
  partner_values.resize((start + n) * width);
  return start;
}

/* Copy the histories of the current neighbour list into per-atom partner lists (both atoms of
   a pair get an entry, the partner's seen with the partner signs). With newton on, entries of
   ghost atoms are sent to their owners (reverse communication). At the end of the step whose
   force call saved the histories before it (save_step), each entry carries those too. */
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
  const bool with_step = saved_step == update->ntimestep && step_values_step == saved_step;
  width = with_step ? 2 * dnum : dnum;

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
      const double *before = with_step ? &step_values[(base + jj) * dnum] : nullptr;
      const int j = jlist[jj] & NEIGHMASK;
      int64_t m = poffset[i] + npartner[i]++;
      partner_tag[m] = tag[j];
      std::memcpy(&partner_values[m * width], one, dnum * sizeof(double));
      if (before) std::memcpy(&partner_values[m * width + dnum], before, dnum * sizeof(double));
      if (j < counted) {
        m = poffset[j] + npartner[j]++;
        partner_tag[m] = tag[i];
        for (int n = 0; n < dnum; n++) partner_values[m * width + n] = signs[n] * one[n];
        if (before)
          for (int n = 0; n < dnum; n++)
            partner_values[m * width + dnum + n] = signs[n] * before[n];
      }
    }
  }
  if (newton_pair) {
    commflag = PERPARTNER;
    comm->reverse_comm_variable(this);
  }
  maxpartner = 0;
  for (int i = 0; i < nlocal_neigh; i++) maxpartner = std::max(maxpartner, npartner[i]);
  maxexchange = (width + 1) * maxpartner + 1 + RECORD;
  for (int i = nlocal_neigh; i < atom->nlocal; i++) npartner[i] = 0;
  partners_current = true;
}

void FixMdrdemHistory::pre_exchange()
{
  collect_partners();
}

/* After a neighbour list is built: each neighbour gets the history found in its atom's partner
   list (by partner tag), or zeroes; so do the histories before the saved step when the partner
   lists carry them. */
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
  const bool with_step = width == 2 * dnum;

  if ((int) neigh_offset.size() < nall_neigh) neigh_offset.resize(nall_neigh);
  int64_t total = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    neigh_offset[i] = total;
    total += numneigh[i];
  }
  touch.assign(total, 0);
  values.assign(total * dnum, 0.0);
  if (with_step) step_values.assign(total * dnum, 0.0);
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
          const double *found = &partner_values[(poffset[i] + m) * width];
          std::memcpy(&values[(base + jj) * dnum], found, dnum * sizeof(double));
          if (with_step)
            std::memcpy(&step_values[(base + jj) * dnum], found + dnum, dnum * sizeof(double));
          break;
        }
      }
    }
  }
  step_values_step = with_step ? saved_step : -1;
  have_neigh = true;
  partners_current = false;
}

/* ----------------------------------------------------------------------
   Continuing a run as if it had not been split.

   LAMMPS's velocity Verlet (Verlet::run) evaluates the forces of step n after the first
   half-kick and the drift, with the half-step velocities v(n-1/2), and the first half-kick of
   step n+1 uses those forces. A new `run` (also after read_restart) recomputes the forces in its
   setup call (Verlet::setup) instead. Evaluating the stored histories there (as LAMMPS's own
   history styles do) gives other forces than step n gave: the dashpots see v(n) instead of
   v(n-1/2), and the Mindlin law's tangential dashpot acts only while its spring sticks, so a
   contact that slipped in step n sits exactly at the Coulomb limit and its zero-increment
   re-evaluation may count it as sticking.

   So the force call of a step that ends a run (or writes a restart file) saves the histories
   before it and the velocities it sees (save_step); the end of the run records the velocities
   the step ended with (post_run). The setup call of the next run at that same step repeats that
   force call (the same histories, velocities and dt, on copies: nothing is written; the
   positions are the same) when every atom still has the velocities the step ended with
   (replay_step). Otherwise (the first run, a command changed velocities, a minimisation) it
   evaluates the stored histories with the current velocities. Histories and records travel with
   their atoms and go to and come from restart files.
------------------------------------------------------------------------- */

void FixMdrdemHistory::save_step()
{
  step_values = values;
  double **v = atom->v, **omega = atom->omega;
  for (int i = 0; i < atom->nlocal; i++)
    for (int c = 0; c < 3; c++) {
      record[i][c] = v[i][c];
      record[i][3 + c] = omega[i][c];
    }
  saved_step = step_values_step = update->ntimestep;
}

void FixMdrdemHistory::post_run()
{
  pre_exchange();
  if (saved_step == update->ntimestep) {
    double **v = atom->v, **omega = atom->omega;
    for (int i = 0; i < atom->nlocal; i++)
      for (int c = 0; c < 3; c++) {
        record[i][6 + c] = v[i][c];
        record[i][9 + c] = omega[i][c];
      }
    record_step = saved_step;
  } else {
    record_step = -1;
  }
}

bool FixMdrdemHistory::replay_step(const double *&v_out, const double *&omega_out,
                                   double *&step_values_out)
{
  const bigint now = update->ntimestep;
  int local = update->whichflag == 1 && record_step == now && step_values_step == now &&
      step_values.size() == values.size();
  double **v = atom->v, **omega = atom->omega;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal && local; i++)
    for (int c = 0; c < 3; c++)
      if (v[i][c] != record[i][6 + c] || omega[i][c] != record[i][9 + c]) local = 0;
  int all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_MIN, world);
  replayed_step = all ? now : -1;
  if (!all) return false;

  const int nall = nlocal + atom->nghost;
  setup_v.resize(3 * (size_t) nall);
  setup_omega.resize(3 * (size_t) nall);
  for (int i = 0; i < nlocal; i++)
    for (int c = 0; c < 3; c++) {
      setup_v[3 * i + c] = record[i][c];
      setup_omega[3 * i + c] = record[i][3 + c];
    }
  comm->forward_comm(this);
  v_out = setup_v.data();
  omega_out = setup_omega.data();
  step_values_out = step_values.data();
  return true;
}

int FixMdrdemHistory::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                        int * /*pbc*/)
{
  double **v = atom->v;
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    for (int c = 0; c < 3; c++) buf[m++] = setup_v[3 * j + c];
    for (int c = 0; c < 3; c++) buf[m++] = setup_omega[3 * j + c];
    for (int c = 0; c < 3; c++) buf[m++] = v[j][c];
  }
  return m;
}

void FixMdrdemHistory::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  int m = 0;
  for (int i = first; i < first + n; i++) {
    // the owner's replayed velocity plus what LAMMPS's own ghost communication added to the
    // owner's current one (zero unless a deforming box remaps velocities)
    for (int c = 0; c < 3; c++) setup_v[3 * i + c] = buf[m + c] + (v[i][c] - buf[m + 6 + c]);
    for (int c = 0; c < 3; c++) setup_omega[3 * i + c] = buf[m + 3 + c];
    m += REPLAY_COMM;
  }
}

/* A restart file carries the record of the saved step when it is written at its end: between
   runs (write_restart) the record post_run() completed, during a run (restart output) the saved
   velocities and the current ones. */
bool FixMdrdemHistory::record_written() const
{
  if (update->whichflag == 1) return saved_step == update->ntimestep;
  return record_step == update->ntimestep;
}

void FixMdrdemHistory::write_restart(FILE *fp)
{
  // During a run (restart output) the neighbour-order histories are newer than the partner
  // lists; between runs post_run() has already collected them (and atoms may have been
  // exchanged since, so the neighbour list must not be read again).
  if (!partners_current) collect_partners();
  if (comm->me == 0) {
    const double state[2] = {record_written() ? (double) update->ntimestep : -1.0,
                             (double) width};
    int size = sizeof(state);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(state, sizeof(double), 2, fp);
  }
}

void FixMdrdemHistory::restart(char *buf)
{
  double state[2];
  std::memcpy(state, buf, sizeof(state));
  saved_step = record_step = (bigint) state[0];
  width = file_width = static_cast<int>(state[1]);
  // A file written without adhesion read by a run with it: its histories lack the attached
  // radius (the last value of each dnum block, crates/mdr-lammps/src/history.rs), which starts
  // at zero (springs attach when they touch).
  const bool adds_adhesion = (dnum == 6 || dnum == 11) &&
      (file_width == dnum - 1 || file_width == 2 * (dnum - 1));
  if (adds_adhesion) width = file_width == dnum - 1 ? dnum : 2 * dnum;
  if (width != dnum && width != 2 * dnum)
    error->all(FLERR, "fix {}: the restart file holds {} history values per contact, not {} or {}",
               id, width, dnum, 2 * dnum);
}

void FixMdrdemHistory::grow_arrays(int nmax)
{
  memory->grow(npartner, nmax, "mdrdem/history:npartner");
  poffset = (int64_t *) memory->srealloc(poffset, nmax * sizeof(int64_t), "mdrdem/history:poffset");
  memory->grow(record, nmax, RECORD, "mdrdem/history:record");
}

void FixMdrdemHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  npartner[j] = npartner[i];
  poffset[j] = poffset[i];
  std::memcpy(record[j], record[i], RECORD * sizeof(double));
}

void FixMdrdemHistory::set_arrays(int i)
{
  npartner[i] = 0;
  poffset[i] = 0;
  for (int c = 0; c < RECORD; c++) record[i][c] = NOT_KNOWN;
}

int FixMdrdemHistory::pack_exchange(int i, double *buf)
{
  int m = 0;
  const int sent = drop_migrated ? 0 : npartner[i];
  buf[m++] = sent;
  for (int n = 0; n < sent; n++) {
    buf[m++] = ubuf(partner_tag[poffset[i] + n]).d;
    std::memcpy(&buf[m], &partner_values[(poffset[i] + n) * width], width * sizeof(double));
    m += width;
  }
  std::memcpy(&buf[m], record[i], RECORD * sizeof(double));
  return m + RECORD;
}

int FixMdrdemHistory::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  npartner[nlocal] = static_cast<int>(buf[m++]);
  maxpartner = std::max(maxpartner, npartner[nlocal]);
  int64_t start = reserve(nlocal, npartner[nlocal]);
  for (int n = 0; n < npartner[nlocal]; n++) {
    partner_tag[start + n] = (tagint) ubuf(buf[m++]).i;
    std::memcpy(&partner_values[(start + n) * width], &buf[m], width * sizeof(double));
    m += width;
  }
  std::memcpy(record[nlocal], &buf[m], RECORD * sizeof(double));
  return m + RECORD;
}

int FixMdrdemHistory::pack_restart(int i, double *buf)
{
  int m = 1;
  buf[m++] = npartner[i];
  for (int n = 0; n < npartner[i]; n++) {
    buf[m++] = ubuf(partner_tag[poffset[i] + n]).d;
    std::memcpy(&buf[m], &partner_values[(poffset[i] + n) * width], width * sizeof(double));
    m += width;
  }
  const bool written = record_written();
  const bool in_run = update->whichflag == 1;
  for (int c = 0; c < 6; c++) buf[m++] = written ? record[i][c] : NOT_KNOWN;
  for (int c = 0; c < 3; c++)
    buf[m++] = !written ? NOT_KNOWN : in_run ? atom->v[i][c] : record[i][6 + c];
  for (int c = 0; c < 3; c++)
    buf[m++] = !written ? NOT_KNOWN : in_run ? atom->omega[i][c] : record[i][9 + c];
  buf[0] = m;    // first value: this fix's count, as every per-atom restart fix writes it
  return m;
}

void FixMdrdemHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int count = static_cast<int>(extra[nlocal][m++]);
  npartner[nlocal] = static_cast<int>(extra[nlocal][m++]);
  if (count != (file_width + 1) * npartner[nlocal] + 2 + RECORD)
    error->one(FLERR, "fix {}: restart file not written by this version of pair_style mdrdem", id);
  maxpartner = std::max(maxpartner, npartner[nlocal]);
  int64_t start = reserve(nlocal, npartner[nlocal]);
  const int blocks = width / dnum;                 // 1, or 2 with the histories before a step
  const int file_dnum = file_width / blocks;       // dnum, or dnum - 1 without the adhesive slot
  for (int n = 0; n < npartner[nlocal]; n++) {
    partner_tag[start + n] = (tagint) ubuf(extra[nlocal][m++]).i;
    double *to = &partner_values[(start + n) * width];
    for (int b = 0; b < blocks; b++) {
      std::memcpy(&to[b * dnum], &extra[nlocal][m], file_dnum * sizeof(double));
      for (int c = file_dnum; c < dnum; c++) to[b * dnum + c] = 0.0;
      m += file_dnum;
    }
  }
  std::memcpy(record[nlocal], &extra[nlocal][m], RECORD * sizeof(double));
}

int FixMdrdemHistory::size_restart(int nlocal)
{
  return (width + 1) * npartner[nlocal] + 2 + RECORD;
}

int FixMdrdemHistory::maxsize_restart()
{
  int all = 0;
  MPI_Allreduce(&maxpartner, &all, 1, MPI_INT, MPI_MAX, world);
  return (width + 1) * all + 2 + RECORD;
}

int FixMdrdemHistory::pack_reverse_comm_size(int n, int first)
{
  int m = 0;
  for (int i = first; i < first + n; i++) m += 1 + (width + 1) * npartner[i];
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
        std::memcpy(&buf[m], &partner_values[(poffset[i] + k) * width], width * sizeof(double));
        m += width;
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
      std::memcpy(&partner_values[kk * width], &buf[m], width * sizeof(double));
      m += width;
    }
  }
}

double FixMdrdemHistory::memory_usage()
{
  double bytes = (double) atom->nmax * (sizeof(int) + sizeof(int64_t) + RECORD * sizeof(double));
  bytes += (double) partner_tag.capacity() * sizeof(tagint);
  bytes += (double) partner_values.capacity() * sizeof(double);
  bytes += (double) neigh_offset.capacity() * sizeof(int64_t);
  bytes += (double) touch.capacity() * sizeof(int) + (double) values.capacity() * sizeof(double);
  bytes += (double) step_values.capacity() * sizeof(double);
  bytes += (double) (setup_v.capacity() + setup_omega.capacity()) * sizeof(double);
  return bytes;
}
