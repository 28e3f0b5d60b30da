// navfn-smt: nav2_util::ParameterHandler (rolling), the base of the plugin's parameter handler:
// it owns the parameters and their mutex.  Dynamic parameter updates are not exercised.
#ifndef NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_PARAMETER_HANDLER_HPP_
#define NAVFN_SMT_PLUGIN_STUB_NAV2_UTIL_PARAMETER_HANDLER_HPP_
#include <mutex>
#include <vector>
#include "nav2_ros_common/lifecycle_node.hpp"
namespace nav2_util
{
template<typename ParamsT>
class ParameterHandler
{
public:
  ParameterHandler(const nav2::LifecycleNode::SharedPtr & node, rclcpp::Logger & logger)
  : node_(node), logger_(logger) {}
  virtual ~ParameterHandler() = default;
  ParamsT * getParams() {return &params_;}
  std::mutex & getMutex() {return mutex_;}
  void activate() {}
  void deactivate() {}

protected:
  virtual void updateParametersCallback(const std::vector<rclcpp::Parameter> & parameters) = 0;
  virtual rcl_interfaces::msg::SetParametersResult
  validateParameterUpdatesCallback(const std::vector<rclcpp::Parameter> & parameters) = 0;
  std::weak_ptr<nav2::LifecycleNode> node_;
  rclcpp::Logger logger_;
  std::mutex mutex_;
  ParamsT params_;
};
}  // namespace nav2_util
#endif
