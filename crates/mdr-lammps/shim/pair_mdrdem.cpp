#include "pair_mdrdem.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "fix_mdrdem_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "output.h"
#include "update.h"
#include "utils.h"

#include "mdrdem.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

static const char *HISTORY_ID = "MDRDEM_HISTORY";
// Placeholder that reserves the history fix's place in the fix list when the pair style is
// defined (replaced by the history fix in init_style), as LAMMPS's granular pair styles reserve
// NEIGH_HISTORY_*_DUMMY: a fix defined later that migrates atoms in pre_exchange (fix balance)
// then runs after the histories are collected into the per-atom partner lists.
static const char *PLACEHOLDER_ID = "MDRDEM_HISTORY_DUMMY";

PairMdrdem::PairMdrdem(LAMMPS *lmp) : Pair(lmp), handle(nullptr), history(nullptr), maxrad(nullptr)
{
  single_enable = 1;
  single_extra = 5;    // force on i (3), normal force, overlap
  svector = new double[single_extra];
  restartinfo = 0;     // pair_style and pair_coeff are given again after read_restart
  finitecutflag = 1;
  no_virial_fdotr_compute = 1;    // the Rust loop tallies the virial pair by pair
  beyond_contact = 0;
  if (modify->get_fix_by_id(HISTORY_ID) == nullptr && modify->get_fix_by_id(PLACEHOLDER_ID) == nullptr)
    modify->add_fix(fmt::format("{} all DUMMY", PLACEHOLDER_ID));
}

PairMdrdem::~PairMdrdem()
{
  delete[] svector;
  mdrdem_free(handle);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    delete[] maxrad;
  }
  // The history fix stays so that a redefined pair_style mdrdem keeps the contacts' histories;
  // a placeholder never replaced goes.
  if (modify->get_fix_by_id(PLACEHOLDER_ID)) modify->delete_fix(PLACEHOLDER_ID);
}

void PairMdrdem::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  maxrad = new double[n + 1];
  handle = mdrdem_new(n);
}

void PairMdrdem::settings(int narg, char **arg)
{
  if (narg != 0)
    error->all(FLERR, "pair_style mdrdem takes no arguments (got '{}'); parameters go on pair_coeff",
               arg[0]);
}

void PairMdrdem::coeff(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "pair_coeff mdrdem: expected I J keyword value ...");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  char err[512];
  const int count = mdrdem_coeff(handle, ilo, ihi, jlo, jhi, narg - 2, arg + 2, err, sizeof(err));
  if (count < 0) error->all(FLERR, "pair_coeff mdrdem: {}", err);
  if (count == 0) error->all(FLERR, "pair_coeff mdrdem: no type pair in {} {}", arg[0], arg[1]);
  for (int i = ilo; i <= ihi; i++)
    for (int j = (jlo > i ? jlo : i); j <= jhi; j++) setflag[i][j] = 1;
}

void PairMdrdem::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "pair_style mdrdem requires atom_style sphere (radius, rmass, omega, torque)");
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "pair_style mdrdem requires ghost atoms store velocity (comm_modify vel yes)");

  // Every type pair's model now (mixing errors name the types), so that the history size is
  // known before the history fix is made.
  char err[512];
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (mdrdem_init_one(handle, i, j, err, sizeof(err)) != 0)
        error->all(FLERR, "pair_style mdrdem: {}", err);
  const int dnum = mdrdem_history_size(handle);

  Fix *fix = modify->get_fix_by_id(HISTORY_ID);
  if (fix == nullptr) {
    const std::string command = fmt::format("{} all MDRDEM/HISTORY {}", HISTORY_ID, dnum);
    if (modify->get_fix_by_id(PLACEHOLDER_ID))
      fix = modify->replace_fix(PLACEHOLDER_ID, command, 1);
    else
      fix = modify->add_fix(command);
  }
  history = dynamic_cast<FixMdrdemHistory *>(fix);
  if (history == nullptr) error->all(FLERR, "fix {} is not the mdrdem history fix", HISTORY_ID);
  if (history->dnum != dnum)
    error->all(FLERR, "pair_style mdrdem: the history holds {} values per contact, the coefficients "
               "need {} (rolling or adhesion switched on or off after contacts were made)",
               history->dnum, dnum);
  history->pair = this;

  // cutoff of each type: its largest radius, including particles fix pour/deposit will insert
  std::vector<double> local(n + 1, 0.0);
  for (const char *style : {"^pour", "^deposit"}) {
    for (auto &ifix : modify->get_fix_by_style(style)) {
      for (int t = 1; t <= n; t++) {
        int itype = t;
        auto *r = (double *) ifix->extract("radius", itype);
        if (r) local[t] = std::max(local[t], *r);
      }
    }
  }
  for (int i = 0; i < atom->nlocal; i++)
    local[atom->type[i]] = std::max(local[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(&local[1], &maxrad[1], n, MPI_DOUBLE, MPI_MAX, world);

  // LAMMPS's size lists keep a pair while its distance is below the radii sum plus the skin. An
  // adhesive neck holds beyond contact (up to the reach of docs/theory.md eq. A11): with a skin
  // below the largest reach the list is cut by type instead, at init_one's cut-off (the largest
  // radii of the two types plus their reach) plus the skin, so a held pair stays listed.
  double reach = 0.0;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      reach = std::max(reach, mdrdem_neck_reach(handle, i, j, maxrad[i], maxrad[j]));
  if (neighbor->skin < reach)
    neighbor->add_request(this);
  else
    neighbor->add_request(this, NeighConst::REQ_SIZE);
}

double PairMdrdem::init_one(int i, int j)
{
  char err[512];
  if (mdrdem_init_one(handle, i, j, err, sizeof(err)) != 0)
    error->all(FLERR, "pair_style mdrdem: {}", err);
  // an adhesive neck holds beyond contact: the cut-off covers its reach for the largest
  // spheres of the two types (the reach grows with the effective radius)
  return maxrad[i] + maxrad[j] + mdrdem_neck_reach(handle, i, j, maxrad[i], maxrad[j]);
}

void PairMdrdem::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  MdrdemAtoms atoms;
  atoms.x = atom->x[0];
  atoms.v = atom->v[0];
  atoms.omega = atom->omega[0];
  atoms.f = atom->f[0];
  atoms.torque = atom->torque[0];
  atoms.radius = atom->radius;
  atoms.rmass = atom->rmass;
  atoms.atom_type = atom->type;
  atoms.nlocal = atom->nlocal;
  atoms.nall = atom->nlocal + atom->nghost;

  // The setup call at the start of every run (and of a minimisation) changes no history, as in
  // LAMMPS's own history styles (shearupdate = 0 in pair gran/*/history, history_update = 0 in
  // pair granular, when update->setupflag): its positions are those of the last step, whose
  // increments the histories already hold. It repeats the force call of the step the last run
  // ended on when nothing changed since (the histories before that step, its velocities and dt;
  // fix_mdrdem_history.cpp says why), else it evaluates the stored histories with no increment.
  const bool setup = update->setupflag != 0 && !history->setup_update;
  double *values = history->values.data();
  double dt = update->dt;
  if (update->setupflag) history->replayed_step = -1;
  if (setup) {
    if (!history->replay_step(atoms.v, atoms.omega, values)) dt = 0.0;
  } else if (update->whichflag == 1 &&
             (update->ntimestep == update->laststep || update->ntimestep == output->next_restart)) {
    // A step that ends a run or writes a restart file: keep what its force call sees.
    history->save_step();
  }

  MdrdemNeighbours nl;
  nl.inum = list->inum;
  nl.ilist = list->ilist;
  nl.numneigh = list->numneigh;
  nl.firstneigh = list->firstneigh;
  nl.neighmask = NEIGHMASK;
  nl.offset = history->neigh_offset.data();
  nl.touch = history->touch.data();
  nl.history = values;
  nl.dnum = history->dnum;
  nl.history_update = setup ? 0 : 1;

  MdrdemTally tally;
  tally.newton_pair = force->newton_pair;
  tally.eflag_global = eflag_global;
  tally.vflag_global = vflag_global;
  tally.eng_vdwl = &eng_vdwl;
  tally.virial = virial;
  tally.eatom = eflag_atom ? eatom : nullptr;
  tally.vatom = vflag_atom ? vatom[0] : nullptr;

  char err[512];
  if (mdrdem_compute(handle, &atoms, &nl, &tally, dt, err, sizeof(err)) != 0)
    error->one(FLERR, "pair_style mdrdem: {}", err);
  history->partners_current = false;
}

double PairMdrdem::single(int i, int j, int itype, int jtype, double rsq, double, double,
                          double &fforce)
{
  for (int m = 0; m < single_extra; m++) svector[m] = 0.0;
  fforce = 0.0;
  double *radius = atom->radius;
  const double radsum = radius[i] + radius[j];
  // apart: no force, unless an adhesive neck still holds (the Rust library decides from the history)
  if (rsq >= radsum * radsum && !mdrdem_adhesive(handle)) return 0.0;

  // The history of pair (i, j) as i sees it: in i's neighbours, or in j's (then seen from j).
  int a = i, b = j, ta = itype, tb = jtype;
  const double *values = nullptr;
  for (int pass = 0; pass < 2 && values == nullptr; pass++) {
    if (pass == 1) { a = j; b = i; ta = jtype; tb = itype; }
    if (a >= atom->nlocal) continue;
    const int *jlist = list->firstneigh[a];
    for (int jj = 0; jj < list->numneigh[a]; jj++)
      if ((jlist[jj] & NEIGHMASK) == b) {
        values = &history->values[(history->neigh_offset[a] + jj) * history->dnum];
        break;
      }
  }
  if (values == nullptr) return 0.0;
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const double rm[4] = {radius[a], radius[b], atom->rmass[a], atom->rmass[b]};
  const double del[3] = {x[a][0] - x[b][0], x[a][1] - x[b][1], x[a][2] - x[b][2]};
  const double vr[3] = {v[a][0] - v[b][0], v[a][1] - v[b][1], v[a][2] - v[b][2]};
  double out[5];
  char err[512];
  if (mdrdem_single(handle, ta, tb, rm, del, vr, omega[a], omega[b], values, out, err,
                    sizeof(err)) != 0)
    error->one(FLERR, "pair_style mdrdem: {}", err);
  const double sign = (a == i) ? 1.0 : -1.0;
  for (int m = 0; m < 3; m++) svector[m] = sign * out[m];
  svector[3] = out[3];
  svector[4] = out[4];
  // fforce · (x_i − x_j) is the normal part of the force on i
  fforce = out[3] / std::sqrt(rsq);
  return 0.0;
}

double PairMdrdem::memory_usage()
{
  return Pair::memory_usage();
}
