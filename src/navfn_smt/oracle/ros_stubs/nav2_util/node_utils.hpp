// navfn-smt: nav2_util::declare_parameter_if_not_declared (humble to kilted), for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_NODE_UTILS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_NODE_UTILS_HPP_
#include <string>
#include "rclcpp_lifecycle/lifecycle_node.hpp"
namespace nav2_util
{
template<typename NodeT>
void declare_parameter_if_not_declared(
  NodeT node, const std::string & name, const rclcpp::ParameterValue & default_value)
{
  if (!node->has_parameter(name)) {node->declare_parameter(name, default_value);}
}
template<typename NodeT>
void declare_parameter_if_not_declared(
  NodeT node, const std::string & name, const rclcpp::ParameterType & type)
{
  if (!node->has_parameter(name)) {node->declare_parameter(name, type);}
}
}  // namespace nav2_util
#endif
