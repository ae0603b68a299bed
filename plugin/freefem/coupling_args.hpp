// The named parameters of dlmfsi(...), the same on mesh and mesh3 spaces: their declaration, how FreeFEM
// hands them over, and the options whose reading does not depend on the dimension.
#pragma once
#include "ff++.hpp"

#include <string>
#include <typeinfo>
#include <vector>

#include "sides/options.hpp"  // the core's CouplingOptions
#include "errors.hpp"

namespace dlmfsi_ff {

class CouplingArgs {
 public:
  static const int n_name_param = 13;
  enum { kC1, kC2, kFluid, kSolid, kMethod, kGradient, kQforder, kTol, kSubdivide, kOutside, kOutsideTol, kThreads, kPart };
  static inline basicAC_F0::name_and_type name_param[n_name_param] = {
      {"c1", &typeid(double)},        {"c2", &typeid(double)},        {"fluid", &typeid(KN_<long>)},
      {"solid", &typeid(KN_<long>)},  {"method", &typeid(string*)},   {"gradient", &typeid(string*)},
      {"qforder", &typeid(long)},     {"tol", &typeid(double)},       {"subdivide", &typeid(long)},
      {"outside", &typeid(string*)},  {"outsidetol", &typeid(double)}, {"threads", &typeid(long)},
      {"part", &typeid(KN_<long>)}};

  // A literal list such as [0,1] arrives as E_Array, an int[int] variable as KN_<long>: the parameters are
  // declared as what was given. With lists, the literal lists of fluid=, solid= and part= are kept entry by
  // entry; without, every literal array is accepted (for the functions that only report an error).
  explicit CouplingArgs(const basicAC_F0& args, bool lists = true) {
    basicAC_F0::name_and_type np[n_name_param];
    for (int i = 0; i < n_name_param; ++i) np[i] = name_param[i];
    for (int i = 0; i < n_name_param; ++i)
      if ((!lists || i == kFluid || i == kSolid || i == kPart) && args.find(np[i].name).left() == atype<E_Array>())
        np[i].type = &typeid(E_Array);
    args.SetNameParam(n_name_param, np, nargs_);
    if (!lists) return;
    for (int i : {int(kFluid), int(kSolid), int(kPart)})
      if (const E_Array* a = dynamic_cast<const E_Array*>(nargs_[i])) {
        for (int e = 0; e < a->size(); ++e) list(i).push_back(to<long>((*a)[e]));
        nargs_[i] = 0;
      }
  }

  template <class T>
  T arg(int i, Stack stack, T otherwise) const {
    return nargs_[i] ? GetAny<T>((*nargs_[i])(stack)) : otherwise;
  }
  std::string text(int i, Stack stack, const char* otherwise) const {
    return nargs_[i] ? *GetAny<string*>((*nargs_[i])(stack)) : std::string(otherwise);
  }
  bool given(int i) const { return nargs_[i] || (is_list(i) && !list(i).empty()); }
  // The entries of an integer list option (fluid, solid, part) as given (64-bit); none when not given.
  std::vector<long> integers(int i, Stack stack) const {
    std::vector<long> out;
    for (Expression e : list(i)) out.push_back(GetAny<long>((*e)(stack)));
    if (nargs_[i]) {
      KN_<long> v = GetAny<KN_<long> >((*nargs_[i])(stack));
      for (int k = 0; k < v.N(); ++k) out.push_back(v[k]);
    }
    return out;
  }

  dlmfsi::CouplingOptions::Gradient gradient(Stack stack) const {
    const std::string gradient = text(kGradient, stack, "chain");
    if (gradient == "chain") return dlmfsi::CouplingOptions::Gradient::Chain;
    if (gradient == "listing") return dlmfsi::CouplingOptions::Gradient::Listing;
    throw dlmfsi::Error("gradient=\"" + gradient + "\": expected \"chain\" or \"listing\"");
  }
  // outside="drop" (true) or "error" (false).
  bool drop_outside(Stack stack) const {
    const std::string outside = text(kOutside, stack, "error");
    if (outside == "drop") return true;
    if (outside != "error") throw dlmfsi::Error("outside=\"" + outside + "\": expected \"error\" or \"drop\"");
    return false;
  }

 private:
  static bool is_list(int i) { return i == kFluid || i == kSolid || i == kPart; }
  std::vector<Expression>& list(int i) { return i == kFluid ? fluid_list_ : (i == kSolid ? solid_list_ : part_list_); }
  const std::vector<Expression>& list(int i) const {
    return i == kFluid ? fluid_list_ : (i == kSolid ? solid_list_ : part_list_);
  }
  Expression nargs_[n_name_param] = {};
  // fluid=[..] / solid=[..] / part=[..] given as literal arrays: one expression per entry.
  std::vector<Expression> fluid_list_, solid_list_, part_list_;
};

}  // namespace dlmfsi_ff
