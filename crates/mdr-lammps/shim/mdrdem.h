/* C ABI of the mdr-lammps Rust library (crates/mdr-lammps/src/ffi.rs, src/compute.rs,
   src/wall.rs). The structs mirror the #[repr(C)] structs there field for field. */
#ifndef MDRDEM_H
#define MDRDEM_H
#include <stddef.h>
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const double *x, *v, *omega;
  double *f, *torque;
  const double *radius, *rmass;
  const int *atom_type;
  int nlocal, nall;
} MdrdemAtoms;

typedef struct {
  int inum;
  const int *ilist;
  const int *numneigh;
  const int *const *firstneigh;
  int neighmask;
  const int64_t *offset;
  int *touch;
  double *history;
  int dnum;
  int history_update; /* 0 in LAMMPS's setup call: forces only, nothing written */
} MdrdemNeighbours;

typedef struct {
  int newton_pair, eflag_global, vflag_global;
  double *eng_vdwl, *virial, *eatom, *vatom;
} MdrdemTally;

/* One wall's sphere-wall contacts in one step (src/wall.rs, MdrdemWallContacts). Each row:
   touch flag, dnum history values, dnum values before the step a run ended on. */
typedef struct {
  int n;
  const int *atom;
  const double *branch;        /* 3n: from the sphere's point on the wall to its centre */
  const double *wall_velocity; /* 3n */
  const double *wall_radius;   /* 2n: principal radii of curvature (0 flat, < 0 concave) */
  double *const *row;          /* n rows of 1 + 2 dnum */
  int dnum;
  int history_update;
  int replay;
  const double *replay_velocity; /* 6 per local atom: v, omega of the replayed step */
} MdrdemWallContacts;

void *mdrdem_new(int ntypes);
void mdrdem_free(void *handle);
int mdrdem_coeff(void *handle, int ilo, int ihi, int jlo, int jhi, int nwords,
                 const char *const *words, char *err, size_t errlen);
int mdrdem_init_one(void *handle, int i, int j, char *err, size_t errlen);
int mdrdem_is_set(const void *handle, int i, int j);
int mdrdem_history_size(const void *handle);
int mdrdem_adhesive(const void *handle);
int mdrdem_partner_signs(int dnum, double *out /* dnum values */);
double mdrdem_neck_reach(const void *handle, int i, int j, double ri, double rj);
int mdrdem_compute(const void *handle, const MdrdemAtoms *atoms, const MdrdemNeighbours *list,
                   const MdrdemTally *tally, double dt, char *err, size_t errlen);
int mdrdem_single(const void *handle, int itype, int jtype, const double *radius_mass /* ri rj mi mj */,
                  const double *delta, const double *relative_velocity, const double *omega_i,
                  const double *omega_j, const double *history, double *out /* 5 */,
                  char *err, size_t errlen);

void *mdrdem_wall_new(int nwords, const char *const *words, char *err, size_t errlen);
void mdrdem_wall_free(void *wall);
int mdrdem_wall_init(void *wall, const void *pair_table, char *err, size_t errlen);
int mdrdem_wall_history_size(const void *wall);
double mdrdem_wall_neck_coefficient(const void *wall, int type);
int mdrdem_wall_compute(const void *wall, const MdrdemAtoms *atoms,
                        const MdrdemWallContacts *contacts, double dt, double *total_force /* 3 */,
                        char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
