/* fix wall/mdrdem; see fix_wall_mdrdem.h and docs/lammps.md. */
#include "fix_wall_mdrdem.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_mdrdem_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "output.h"
#include "pair.h"
#include "pair_mdrdem.h"
#include "region.h"
#include "update.h"
#include "utils.h"

#include "mdrdem.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static constexpr double BIG = 1.0e20;

static bool is_wall_style(const char *word)
{
  return strcmp(word, "xplane") == 0 || strcmp(word, "yplane") == 0 ||
      strcmp(word, "zplane") == 0 || strcmp(word, "zcylinder") == 0 ||
      strcmp(word, "region") == 0;
}

static int dimension_of(const char *word)
{
  if (strcmp(word, "x") == 0) return 0;
  if (strcmp(word, "y") == 0) return 1;
  if (strcmp(word, "z") == 0) return 2;
  return -1;
}

FixWallMdrdem::FixWallMdrdem(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), wall(nullptr), region(nullptr), wiggle(0), wshear(0), axis(0),
    amplitude(0.0), period(0.0), wiggle_omega(0.0), vshear(0.0), ncontact(nullptr),
    slots(nullptr), before_step(-1), file_dnum(0), drop_migrated(false), history(nullptr), total_flag(0)
{
  // the law's keywords up to the wall style, checked by the Rust library (errors name them)
  int iarg = 3;
  while (iarg < narg && !is_wall_style(arg[iarg])) iarg++;
  if (iarg == narg)
    error->all(FLERR, "fix wall/mdrdem: expected a wall style (xplane, yplane, zplane, zcylinder "
               "or region) after the keywords");
  char err[512];
  wall = mdrdem_wall_new(iarg - 3, arg + 3, err, sizeof(err));
  if (wall == nullptr) error->all(FLERR, "fix wall/mdrdem: {}", err);
  dnum = mdrdem_wall_history_size(wall);
  file_dnum = dnum;
  width = 2 + 2 * dnum;

  const std::string style = arg[iarg];
  lo = -BIG;
  hi = BIG;
  cylradius = 0.0;
  region_curvature = FLAT;
  if (style == "xplane" || style == "yplane" || style == "zplane") {
    wallstyle = style == "xplane" ? XPLANE : style == "yplane" ? YPLANE : ZPLANE;
    if (iarg + 3 > narg) error->all(FLERR, "fix wall/mdrdem: {} needs lo and hi (a number or NULL)", style);
    lo = number((style + " lo").c_str(), arg[iarg + 1], true, -BIG);
    hi = number((style + " hi").c_str(), arg[iarg + 2], true, BIG);
    if (lo >= hi) error->all(FLERR, "fix wall/mdrdem: {} lo must be below hi", style);
    tmax = 2;
    iarg += 3;
  } else if (style == "zcylinder") {
    wallstyle = ZCYLINDER;
    if (iarg + 2 > narg) error->all(FLERR, "fix wall/mdrdem: zcylinder needs its radius");
    cylradius = number("zcylinder radius", arg[iarg + 1], false, 0.0);
    if (cylradius <= 0.0)
      error->all(FLERR, "fix wall/mdrdem: zcylinder radius must be > 0 (got {})", arg[iarg + 1]);
    tmax = 1;
    iarg += 2;
  } else {
    wallstyle = REGION;
    if (iarg + 2 > narg) error->all(FLERR, "fix wall/mdrdem: region needs a region ID");
    set_region(arg[iarg + 1]);
    tmax = region->tmax;
    iarg += 2;
  }

  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (word == "wiggle") {
      if (iarg + 4 > narg) error->all(FLERR, "fix wall/mdrdem: wiggle needs dim amplitude period");
      axis = dimension_of(arg[iarg + 1]);
      if (axis < 0) error->all(FLERR, "fix wall/mdrdem: wiggle dim must be x, y or z (got {})", arg[iarg + 1]);
      amplitude = number("wiggle amplitude", arg[iarg + 2], false, 0.0);
      period = number("wiggle period", arg[iarg + 3], false, 0.0);
      if (period <= 0.0) error->all(FLERR, "fix wall/mdrdem: wiggle period must be > 0 (got {})", arg[iarg + 3]);
      wiggle = 1;
      iarg += 4;
    } else if (word == "shear") {
      if (iarg + 3 > narg) error->all(FLERR, "fix wall/mdrdem: shear needs dim velocity");
      axis = dimension_of(arg[iarg + 1]);
      if (axis < 0) error->all(FLERR, "fix wall/mdrdem: shear dim must be x, y or z (got {})", arg[iarg + 1]);
      vshear = number("shear velocity", arg[iarg + 2], false, 0.0);
      wshear = 1;
      iarg += 3;
    } else if (is_wall_style(arg[iarg])) {
      error->all(FLERR, "fix wall/mdrdem: one wall style per fix ({} given after {})", word, style);
    } else {
      error->all(FLERR, "fix wall/mdrdem: unknown keyword {} after the wall style (known: wiggle, shear)",
                 word);
    }
  }

  const int periodic[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  if (wallstyle <= ZPLANE && periodic[wallstyle])
    error->all(FLERR, "fix wall/mdrdem: {} in a periodic dimension", style);
  if (wallstyle == ZCYLINDER && (periodic[0] || periodic[1]))
    error->all(FLERR, "fix wall/mdrdem: zcylinder needs non-periodic x and y");
  if (wiggle && wshear) error->all(FLERR, "fix wall/mdrdem: wiggle and shear cannot both be given");
  if (wiggle && wallstyle == ZCYLINDER && axis != 2)
    error->all(FLERR, "fix wall/mdrdem: wiggle of a zcylinder must be along z");
  if (wshear && wallstyle <= ZPLANE && axis == wallstyle)
    error->all(FLERR, "fix wall/mdrdem: shear of {} must be along the plane, not normal to it", style);
  if ((wiggle || wshear) && wallstyle == REGION)
    error->all(FLERR, "fix wall/mdrdem: wiggle and shear are for planes and zcylinder; move a "
               "region with the region command's move and rotate keywords");
  if (wiggle) wiggle_omega = 2.0 * M_PI / period;

  vector_flag = 1;
  size_vector = 3;
  global_freq = 1;
  extvector = 1;
  restart_peratom = 1;
  restart_global = 1;
  create_attribute = 1;
  maxexchange = 1 + tmax * width;
  time_origin = update->ntimestep;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
  for (int c = 0; c < 3; c++) total_local[c] = total_all[c] = 0.0;
}

FixWallMdrdem::~FixWallMdrdem()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(ncontact);
  memory->destroy(slots);
  mdrdem_wall_free(wall);
}

/* A number of the fix line; `what` names it in the error. */
double FixWallMdrdem::number(const char *what, const char *text, bool null_allowed,
                             double null_value)
{
  if (null_allowed && strcmp(text, "NULL") == 0) return null_value;
  char *end = nullptr;
  const double value = strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value))
    error->all(FLERR, "fix wall/mdrdem: {}: expected a number{}, got '{}'", what,
               null_allowed ? " or NULL" : "", text);
  return value;
}

int FixWallMdrdem::setmask()
{
  return POST_FORCE;
}

void FixWallMdrdem::init()
{
  auto *pair = dynamic_cast<PairMdrdem *>(force->pair);
  if (pair == nullptr)
    error->all(FLERR, "fix wall/mdrdem requires pair_style mdrdem (the spheres' materials are its "
               "pair_coeff I I lines)");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "fix wall/mdrdem requires atom_style sphere");
  char err[512];
  if (mdrdem_wall_init(wall, pair->table(), err, sizeof(err)) != 0)
    error->all(FLERR, "fix wall/mdrdem: {}", err);
  history = dynamic_cast<FixMdrdemHistory *>(modify->get_fix_by_id("MDRDEM_HISTORY"));
  neck_coefficient.assign(atom->ntypes + 1, 0.0);
  for (int t = 1; t <= atom->ntypes; t++) neck_coefficient[t] = mdrdem_wall_neck_coefficient(wall, t);
  if (wallstyle == REGION) {
    const std::string id = idregion;
    set_region(id.c_str());
    if (region->tmax > tmax)
      error->all(FLERR, "fix wall/mdrdem: region {} changed its shape", idregion);
  }
}

void FixWallMdrdem::setup(int vflag)
{
  post_force(vflag);
}

/* The wall surfaces within the neighbour skin of sphere i (LAMMPS's fix wall/gran geometry for
   planes and the z cylinder, the region's own surface() for a region). */
void FixWallMdrdem::candidates(int i, double wlo, double whi, const double *vwall_base,
                               std::vector<Candidate> &out)
{
  out.clear();
  double *x = atom->x[i];
  // An adhesive neck holds up to c R^(1/3) beyond contact (docs/theory.md eq. A11), R the
  // effective radius: the sphere's on a plane; on a curved wall the bound R = 100 r covers every
  // wall whose concave radius exceeds the sphere's by more than 1 %.
  const double r = atom->radius[i];
  const double c_neck = neck_coefficient[atom->type[i]];
  const double neck = c_neck > 0.0 ? c_neck * std::cbrt(wallstyle <= ZPLANE ? r : 100.0 * r) : 0.0;
  const double reach = r + neighbor->skin + neck;
  Candidate c;
  if (wallstyle <= ZPLANE) {
    const int a = wallstyle;
    const double sides[2][2] = {{x[a] - wlo, 1.0}, {whi - x[a], -1.0}};
    for (int side = 0; side < 2; side++) {
      const double gap = sides[side][0];
      if (gap <= 0.0 || gap >= reach) continue;
      c.iwall = side;
      c.branch[0] = c.branch[1] = c.branch[2] = 0.0;
      c.branch[a] = sides[side][1] * gap;
      for (int d = 0; d < 3; d++) c.vwall[d] = vwall_base[d];
      c.radii[0] = c.radii[1] = 0.0;
      out.push_back(c);
    }
  } else if (wallstyle == ZCYLINDER) {
    const double rho = std::sqrt(x[0] * x[0] + x[1] * x[1]);
    if (rho == 0.0) return;
    const double gap = std::fabs(cylradius - rho);
    if (gap >= reach) return;
    c.iwall = 0;
    const double scale = 1.0 - cylradius / rho;
    c.branch[0] = scale * x[0];
    c.branch[1] = scale * x[1];
    c.branch[2] = 0.0;
    for (int d = 0; d < 3; d++) c.vwall[d] = vwall_base[d];
    if (wshear && axis != 2) {
      // the cylinder turns about its axis with surface speed vshear (clockwise seen from +z)
      c.vwall[0] = vshear * x[1] / rho;
      c.vwall[1] = -vshear * x[0] / rho;
      c.vwall[2] = 0.0;
    }
    c.radii[0] = rho < cylradius ? -cylradius : cylradius;
    c.radii[1] = 0.0;
    out.push_back(c);
  } else {
    if (!region->match(x[0], x[1], x[2])) return;
    const int nc = region->surface(x[0], x[1], x[2], reach);
    if (nc > tmax) error->one(FLERR, "fix wall/mdrdem: too many contacts of one sphere with region {}", idregion);
    const std::size_t first = out.size();
    for (int ic = 0; ic < nc; ic++) {
      auto &rc = region->contact[ic];
      if (rc.r <= 0.0) continue;
      c.iwall = rc.iwall;
      c.branch[0] = rc.delx;
      c.branch[1] = rc.dely;
      c.branch[2] = rc.delz;
      c.vwall[0] = c.vwall[1] = c.vwall[2] = 0.0;
      if (region->dynamic_check()) region->velocity_contact(c.vwall, x, ic);
      // The wall's principal radii of curvature (0 flat, negative concave) from the size
      // LAMMPS's regions report (Region::Contact::radius, 0 on flat faces): a sphere its radius,
      // negative inside (RegSphere), both directions alike; a cylinder twice its radius,
      // negative inside (RegCylinder), straight along its axis; a cone twice its radius at the
      // contact point, negative on both sides (RegCone), so the side is the region's.
      c.radii[0] = c.radii[1] = 0.0;
      if (region_curvature == SPHERE) {
        c.radii[0] = c.radii[1] = rc.radius;
      } else if (region_curvature == CYLINDER) {
        c.radii[0] = 0.5 * rc.radius;
      } else if (region_curvature == CONE && rc.radius != 0.0) {
        c.radii[0] = (region->interior ? -0.5 : 0.5) * std::fabs(rc.radius);
      }
      out.push_back(c);
    }
    // A cone's side curves around the axis with radius rho / cos(half angle) (Meusnier: the
    // circle of radius rho about the axis is tilted by the half angle from the side's normal
    // section) and is straight along the side. After the loop: cone_secant asks the region again.
    if (region_curvature == CONE)
      for (std::size_t k = first; k < out.size(); k++)
        if (out[k].radii[0] != 0.0)
          out[k].radii[0] *= cone_secant(x, out[k].branch, std::fabs(out[k].radii[0]), reach);
  }
}

/* The region of a `region ID` wall, refused by name where its contacts do not say how the wall
   curves: the styles whose Region::Contact::radius is the curvature the law needs (block, plane
   and prism flat; sphere, cylinder and cone curved), not an ellipsoid (one size for two
   principal curvatures) or a union or intersection (which does not say which member a contact
   is on). */
void FixWallMdrdem::set_region(const char *id)
{
  idregion = id;
  region = domain->get_region_by_id(idregion);
  if (region == nullptr) error->all(FLERR, "fix wall/mdrdem: region {} does not exist", idregion);
  const char *style = region->style;
  if (strcmp(style, "block") == 0 || strcmp(style, "plane") == 0 || strcmp(style, "prism") == 0)
    region_curvature = FLAT;
  else if (strcmp(style, "sphere") == 0)
    region_curvature = SPHERE;
  else if (strcmp(style, "cylinder") == 0)
    region_curvature = CYLINDER;
  else if (strcmp(style, "cone") == 0)
    region_curvature = CONE;
  else
    error->all(FLERR,
               "fix wall/mdrdem: region {} is of style {}, whose contacts do not give the wall's "
               "curvature; the region styles of a wall are block, plane, prism, sphere, cylinder "
               "and cone",
               idregion, style);
}

/* 1 / cos(half angle) of the cone's side at the contact of the sphere at x (branch: from the
   contact point to x, rho: the cone's radius there). The cone's radius grows by sin(half angle)
   per unit length along the side and not around the axis, so its radius at the contact points of
   two spheres moved off x across the normal by eps gives sin(half angle). */
double FixWallMdrdem::cone_secant(const double *x, const double *branch, double rho, double reach)
{
  const double len = std::sqrt(branch[0] * branch[0] + branch[1] * branch[1] + branch[2] * branch[2]);
  const double n[3] = {branch[0] / len, branch[1] / len, branch[2] / len};
  // t1: the coordinate axis least along n, made normal to n; t2 = n x t1
  int a = 0;
  for (int d = 1; d < 3; d++)
    if (std::fabs(n[d]) < std::fabs(n[a])) a = d;
  double t1[3] = {-n[a] * n[0], -n[a] * n[1], -n[a] * n[2]};
  t1[a] += 1.0;
  const double l1 = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (double &t : t1) t /= l1;
  const double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                        n[0] * t1[1] - n[1] * t1[0]};
  const double eps = 1.0e-6 * rho;
  double sin2 = 0.0;
  for (const double *t : {static_cast<const double *>(t1), t2}) {
    double xp[3] = {x[0] + eps * t[0], x[1] + eps * t[1], x[2] + eps * t[2]};
    const int nc = region->surface(xp[0], xp[1], xp[2], reach);
    double rho_p = -1.0;
    for (int ic = 0; ic < nc; ic++)
      if (region->contact[ic].radius != 0.0) rho_p = 0.5 * std::fabs(region->contact[ic].radius);
    if (rho_p < 0.0)
      error->one(FLERR, "fix wall/mdrdem: region {}: the cone's side is not found next to a contact",
                 idregion);
    const double slope = (rho_p - rho) / eps;
    sin2 += slope * slope;
  }
  return 1.0 / std::sqrt(std::max(1.0 - sin2, 1.0e-12));
}

double *FixWallMdrdem::find_slot(int i, int iwall)
{
  for (int k = 0; k < ncontact[i]; k++)
    if (static_cast<int>(slots[i][k * width]) == iwall) return &slots[i][k * width];
  return nullptr;
}

/* One step (or LAMMPS's setup call of a run, which changes no history, as pair_style mdrdem's:
   it repeats the force call of the step the last run ended on when the pair style does, else it
   evaluates the stored histories with dt = 0). */
void FixWallMdrdem::post_force(int /*vflag*/)
{
  const bool setup = update->setupflag != 0;
  const bigint now = update->ntimestep;
  const double dt = update->dt;

  // the wall's position and velocity (fix wall/gran's wiggle and shear)
  double wlo = lo, whi = hi;
  double vwall[3] = {0.0, 0.0, 0.0};
  if (wiggle) {
    const double phase = wiggle_omega * (now - time_origin) * dt;
    if (wallstyle == axis) {
      if (lo > -BIG) wlo = lo + amplitude - amplitude * cos(phase);
      if (hi < BIG) whi = hi + amplitude - amplitude * cos(phase);
    }
    vwall[axis] = amplitude * wiggle_omega * sin(phase);
  } else if (wshear) {
    vwall[axis] = vshear;
  }
  if (wallstyle == REGION && region->dynamic_check()) {
    region->prematch();
    region->set_velocity();
  }

  // A step that ends a run or writes a restart file keeps the histories before it.
  const bool save = !setup && update->whichflag == 1 &&
      (now == update->laststep || now == output->next_restart);
  const bool replay = setup && history != nullptr && history->replayed_step == now &&
      before_step == now;

  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  c_atom.clear();
  c_branch.clear();
  c_vwall.clear();
  c_radius.clear();
  c_row.clear();
  if (setup) c_scratch.assign((size_t) nlocal * tmax * (1 + 2 * dnum), 0.0);
  // A sphere without wall histories whose centre is beyond reach of both planes has nothing to
  // do (most of a bed on a floor): skip it before the general candidate search.
  double **x = atom->x;
  double *radius = atom->radius;
  int *type = atom->type;
  const double skin = neighbor->skin;
  const bool adhesive = std::any_of(neck_coefficient.begin(), neck_coefficient.end(),
                                    [](double c) { return c > 0.0; });
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (wallstyle <= ZPLANE && ncontact[i] == 0) {
      const double r = radius[i];
      const double reach =
          r + skin + (adhesive ? neck_coefficient[type[i]] * std::cbrt(r) : 0.0);
      const double xa = x[i][wallstyle];
      if (xa - wlo >= reach && whi - xa >= reach) continue;
    }
    candidates(i, wlo, whi, vwall, found);
    if (!setup) {
      if (found.empty()) {
        ncontact[i] = 0;
        continue;
      }
      // keep the slots of the walls still in reach (in the order found), forget the others
      kept.assign((size_t) found.size() * width, 0.0);
      for (size_t k = 0; k < found.size(); k++) {
        double *slot = find_slot(i, found[k].iwall);
        if (slot) std::memcpy(&kept[k * width], slot, width * sizeof(double));
        kept[k * width] = found[k].iwall;
      }
      ncontact[i] = static_cast<int>(found.size());
      if (!kept.empty()) std::memcpy(slots[i], kept.data(), kept.size() * sizeof(double));
      if (save)
        for (int k = 0; k < ncontact[i]; k++)
          std::memcpy(&slots[i][k * width + 2 + dnum], &slots[i][k * width + 2],
                      dnum * sizeof(double));
    }
    for (size_t k = 0; k < found.size(); k++) {
      double *slot = find_slot(i, found[k].iwall);
      // in a setup call a surface without a slot is evaluated as a new contact, on a copy
      double *row = slot ? slot + 1 : &c_scratch[((size_t) i * tmax + k) * (1 + 2 * dnum)];
      c_atom.push_back(i);
      c_row.push_back(row);
      for (int d = 0; d < 3; d++) c_branch.push_back(found[k].branch[d]);
      for (int d = 0; d < 3; d++) c_vwall.push_back(found[k].vwall[d]);
      c_radius.push_back(found[k].radii[0]);
      c_radius.push_back(found[k].radii[1]);
    }
  }
  if (save) before_step = now;

  if (replay) {
    c_replay.resize(6 * (size_t) nlocal);
    for (int i = 0; i < nlocal; i++) std::memcpy(&c_replay[6 * i], history->step_velocity(i), 6 * sizeof(double));
  }

  MdrdemAtoms atoms;
  atoms.x = atom->x[0];
  atoms.v = atom->v[0];
  atoms.omega = atom->omega[0];
  atoms.f = atom->f[0];
  atoms.torque = atom->torque[0];
  atoms.radius = atom->radius;
  atoms.rmass = atom->rmass;
  atoms.atom_type = atom->type;
  atoms.nlocal = nlocal;
  atoms.nall = nlocal + atom->nghost;

  MdrdemWallContacts contacts;
  contacts.n = static_cast<int>(c_atom.size());
  contacts.atom = c_atom.data();
  contacts.branch = c_branch.data();
  contacts.wall_velocity = c_vwall.data();
  contacts.wall_radius = c_radius.data();
  contacts.row = c_row.data();
  contacts.dnum = dnum;
  contacts.history_update = setup ? 0 : 1;
  contacts.replay = replay ? 1 : 0;
  contacts.replay_velocity = replay ? c_replay.data() : nullptr;

  char err[512];
  if (mdrdem_wall_compute(wall, &atoms, &contacts, (setup && !replay) ? 0.0 : dt, total_local,
                          err, sizeof(err)) != 0)
    error->one(FLERR, "fix wall/mdrdem: {}", err);
  total_flag = 0;
}

double FixWallMdrdem::compute_vector(int n)
{
  if (total_flag == 0) {
    MPI_Allreduce(total_local, total_all, 3, MPI_DOUBLE, MPI_SUM, world);
    total_flag = 1;
  }
  return total_all[n];
}

int FixWallMdrdem::modify_param(int narg, char **arg)
{
  // Test hook: a sphere sent to another rank arrives without its wall histories. The tests use
  // it to show that their comparison detects histories left behind.
  if (strcmp(arg[0], "drop_migrated") == 0) {
    if (narg < 2) error->all(FLERR, "fix_modify drop_migrated needs yes or no");
    drop_migrated = utils::logical(FLERR, arg[1], false, lmp) == 1;
    return 2;
  }
  return 0;
}

/* Global restart: the wiggle's time origin, the step of the saved histories, the layout, and a
   region's motion (as fix wall/gran/region writes it). */
void FixWallMdrdem::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const double state[3] = {(double) time_origin, (double) before_step, (double) dnum};
  int len = 0;
  if (region) region->length_restart_string(len);
  int size = (int) sizeof(state) + len;
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(state, sizeof(double), 3, fp);
  if (region) region->write_restart(fp);
}

void FixWallMdrdem::restart(char *buf)
{
  double state[3];
  std::memcpy(state, buf, sizeof(state));
  time_origin = (bigint) state[0];
  before_step = (bigint) state[1];
  file_dnum = (int) state[2];
  // A file written without adhesion read by a fix line with it: the attached radius (the last
  // value of each history) starts at zero.
  const bool adds_adhesion = (dnum == 6 || dnum == 11) && file_dnum == dnum - 1;
  if (file_dnum != dnum && !adds_adhesion)
    error->all(FLERR, "fix {}: the restart file holds {} history values per wall contact, the "
               "fix line needs {} (rolling or adhesion switched on or off)", id, file_dnum, dnum);
  if (region) {
    int n = (int) sizeof(state);
    if (!region->restart(buf, n)) {
      error->warning(FLERR, "fix {}: region {} differs from the restart file's, its motion restarts",
                     id, idregion);
      region->reset_vel();
    }
  }
}

void FixWallMdrdem::grow_arrays(int nmax)
{
  memory->grow(ncontact, nmax, "wall/mdrdem:ncontact");
  memory->grow(slots, nmax, tmax * width, "wall/mdrdem:slots");
}

void FixWallMdrdem::copy_arrays(int i, int j, int /*delflag*/)
{
  ncontact[j] = ncontact[i];
  std::memcpy(slots[j], slots[i], (size_t) ncontact[i] * width * sizeof(double));
}

void FixWallMdrdem::set_arrays(int i)
{
  ncontact[i] = 0;
}

int FixWallMdrdem::pack_exchange(int i, double *buf)
{
  const int sent = drop_migrated ? 0 : ncontact[i];
  buf[0] = sent;
  std::memcpy(&buf[1], slots[i], (size_t) sent * width * sizeof(double));
  return 1 + sent * width;
}

int FixWallMdrdem::unpack_exchange(int nlocal, double *buf)
{
  ncontact[nlocal] = static_cast<int>(buf[0]);
  std::memcpy(slots[nlocal], &buf[1], (size_t) ncontact[nlocal] * width * sizeof(double));
  return 1 + ncontact[nlocal] * width;
}

int FixWallMdrdem::pack_restart(int i, double *buf)
{
  const int n = 2 + ncontact[i] * width;
  buf[0] = n;    // first value: this fix's count, as every per-atom restart fix writes it
  buf[1] = ncontact[i];
  std::memcpy(&buf[2], slots[i], (size_t) ncontact[i] * width * sizeof(double));
  return n;
}

void FixWallMdrdem::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int count = static_cast<int>(extra[nlocal][m]);
  const int n = static_cast<int>(extra[nlocal][m + 1]);
  const int file_slot = 2 + 2 * file_dnum;
  if (n < 0 || n > tmax || count != 2 + n * file_slot)
    error->one(FLERR, "fix {}: the restart file's wall histories do not fit this fix line", id);
  ncontact[nlocal] = n;
  // slot: wall id, touch flag, the history, the history before the saved step (each padded
  // with the zero attached radius when the file has none)
  for (int k = 0; k < n; k++) {
    const double *from = &extra[nlocal][m + 2 + k * file_slot];
    double *to = &slots[nlocal][k * width];
    to[0] = from[0];
    to[1] = from[1];
    for (int b = 0; b < 2; b++) {
      for (int c = 0; c < dnum; c++)
        to[2 + b * dnum + c] = c < file_dnum ? from[2 + b * file_dnum + c] : 0.0;
    }
  }
}

int FixWallMdrdem::size_restart(int nlocal)
{
  return 2 + ncontact[nlocal] * width;
}

int FixWallMdrdem::maxsize_restart()
{
  return 2 + tmax * width;
}

double FixWallMdrdem::memory_usage()
{
  return (double) atom->nmax * (sizeof(int) + (double) tmax * width * sizeof(double));
}
