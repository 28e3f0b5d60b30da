// navfn-smt: nav2::declare_parameter_if_not_declared (rolling): nav2_util's, under its new name.
#ifndef NAVFN_SMT_PLUGIN_STUB_NAV2_NODE_UTILS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_NAV2_NODE_UTILS_HPP_
#include "nav2_util/node_utils.hpp"
namespace nav2
{
using nav2_util::declare_parameter_if_not_declared;
}
#endif
