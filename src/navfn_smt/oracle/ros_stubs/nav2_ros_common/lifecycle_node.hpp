// navfn-smt: nav2_ros_common's lifecycle node (rolling), for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_NAV2_LIFECYCLE_NODE_HPP_
#define NAVFN_SMT_PLUGIN_STUB_NAV2_LIFECYCLE_NODE_HPP_
#include <string>
#include "rclcpp_lifecycle/lifecycle_node.hpp"
#include "nav2_ros_common/qos_profiles.hpp"
namespace nav2
{
template<typename MessageT>
using Subscription = rclcpp::Subscription<MessageT>;

class LifecycleNode : public rclcpp_lifecycle::LifecycleNode
{
public:
  using SharedPtr = std::shared_ptr<LifecycleNode>;
  using WeakPtr = std::weak_ptr<LifecycleNode>;
  using rclcpp_lifecycle::LifecycleNode::LifecycleNode;
  // declare the parameter unless it is declared, then read it
  template<typename T>
  T declare_or_get_parameter(const std::string & name, const T & default_value)
  {
    if (!has_parameter(name)) {declare_parameter(name, rclcpp::ParameterValue(default_value));}
    T out{};
    get_parameter(name, out);
    return out;
  }
};
}  // namespace nav2
#endif
