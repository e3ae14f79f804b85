/* pair_style mdrdem: the C++ shim LAMMPS needs around the Rust library of mdr-lammps. Parsing,
   range checks, mixing and every force come from Rust (mdr-contact's ContactLaw) through the C
   ABI of mdrdem.h, one call per neighbour list. */
#ifndef MDRDEM_PAIR_H
#define MDRDEM_PAIR_H

#include "pair.h"

namespace LAMMPS_NS {

class PairMdrdem : public Pair {
 public:
  PairMdrdem(class LAMMPS *);
  ~PairMdrdem() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  double single(int, int, int, int, double, double, double, double &) override;
  double memory_usage() override;
  const void *table() const { return handle; }    // the coefficient table (for the wall fix)

 protected:
  void allocate();
  void *handle;                        // the Rust coefficient table
  class FixMdrdemHistory *history;     // the plugin's own history fix
  double *maxrad;                      // largest radius of each type (cutoffs)
};

}    // namespace LAMMPS_NS
#endif
