// Names of the friction laws, from the laws table (friction_law.h).
#include "nonsmooth_sim/core/friction_law.h"

#include "nonsmooth_sim/core/enum_names.h"

namespace nonsmooth_sim {

std::optional<FrictionSet> FrictionSetFromName(std::string_view name) {
  return EnumFromName(name, kAllFrictionSets, &FrictionSetName);
}

std::string FrictionSetNameList() { return EnumNameList(kAllFrictionSets, &FrictionSetName); }

}  // namespace nonsmooth_sim
