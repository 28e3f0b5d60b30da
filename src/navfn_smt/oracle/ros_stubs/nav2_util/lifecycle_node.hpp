// navfn-smt: nav2_util's lifecycle node (humble to kilted), for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_LIFECYCLE_NODE_HPP_
#define NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_LIFECYCLE_NODE_HPP_
#include "rclcpp_lifecycle/lifecycle_node.hpp"
namespace nav2_util
{
using LifecycleNode = rclcpp_lifecycle::LifecycleNode;
}
#endif
