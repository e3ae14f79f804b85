/* fix wall/mdrdem: the MDR law of pair_style mdrdem between spheres and a wall (a half-space of
   its own material): planes, a z cylinder or any LAMMPS region (moving and rotating regions
   included), with wiggle and shear motion, the geometry of LAMMPS's fix wall/gran and
   fix wall/gran/region. Every force comes from the Rust library (src/wall.rs) through the C ABI
   of mdrdem.h, one call per step. Each sphere carries the histories of its wall contacts
   (per-atom slots that migrate with it and go to and come from restart files). */
#ifndef MDRDEM_FIX_WALL_H
#define MDRDEM_FIX_WALL_H

#include "fix.h"
#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallMdrdem : public Fix {
 public:
  FixWallMdrdem(class LAMMPS *, int, char **);
  ~FixWallMdrdem() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int modify_param(int, char **) override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

 private:
  enum WallStyle { XPLANE = 0, YPLANE = 1, ZPLANE = 2, ZCYLINDER, REGION };
  // How a region style's contacts carry the wall's curvature (Region::Contact::radius).
  enum RegionCurvature { FLAT, SPHERE, CYLINDER, CONE };
  struct Candidate {    // one wall surface within the neighbour skin of a sphere
    int iwall;
    double branch[3], vwall[3], radii[2];
  };

  double number(const char *what, const char *text, bool null_allowed, double null_value);
  void candidates(int i, double wlo, double whi, const double *vwall_base,
                  std::vector<Candidate> &out);
  double *find_slot(int i, int iwall);
  void set_region(const char *id);
  double cone_secant(const double *x, const double *branch, double rho, double reach);

  void *wall;    // the Rust wall (its line and per-type models)
  int dnum;      // history values per contact
  int width;     // doubles per slot: wall id, touch, dnum values, dnum values before the step
  int tmax;      // slots per atom
  int wallstyle;
  double lo, hi, cylradius;
  std::string idregion;
  class Region *region;
  int region_curvature;
  int wiggle, wshear, axis;
  double amplitude, period, wiggle_omega, vshear;
  bigint time_origin;

  int *ncontact;    // per atom: slots in use
  double **slots;   // per atom: tmax slots of `width`
  bigint before_step;    // the step whose histories before it the slots hold (-1: none)
  int file_dnum;         // history values per contact in the restart file being read
  bool drop_migrated;    // test hook: a sphere moving to another rank arrives without histories

  class FixMdrdemHistory *history;
  double total_local[3], total_all[3];
  int total_flag;

  std::vector<double> neck_coefficient;    // per type: c of the adhesive reach c R^(1/3)
  std::vector<Candidate> found;
  std::vector<double> kept;
  std::vector<int> c_atom;
  std::vector<double> c_branch, c_vwall, c_radius, c_replay, c_scratch;
  std::vector<double *> c_row;
};

}    // namespace LAMMPS_NS
#endif
