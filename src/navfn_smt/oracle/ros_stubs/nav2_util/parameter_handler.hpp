// navfn-smt: nav2_util::ParameterHandler (rolling), the base of the plugin's parameter handler:
// it owns the parameters and their mutex; while active, a parameter request is validated by
// the handler's validate callback and applied by its update callback, as Nav2's handler
// registers them on the node (the plugin's runs never send one; Nav2's own tests do).
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
  void activate()
  {
    auto node = node_.lock();
    if (!node) {return;}
    on_set_ = node->add_on_set_parameters_callback(
      [this](const std::vector<rclcpp::Parameter> & p) {return validateParameterUpdatesCallback(p);});
    post_set_ = node->add_post_set_parameters_callback(
      [this](const std::vector<rclcpp::Parameter> & p) {updateParametersCallback(p);});
  }
  void deactivate()
  {
    auto node = node_.lock();
    if (node && on_set_) {node->remove_on_set_parameters_callback(on_set_.get());}
    if (node && post_set_) {node->remove_post_set_parameters_callback(post_set_.get());}
    on_set_.reset();
    post_set_.reset();
  }

protected:
  virtual void updateParametersCallback(const std::vector<rclcpp::Parameter> & parameters) = 0;
  virtual rcl_interfaces::msg::SetParametersResult
  validateParameterUpdatesCallback(const std::vector<rclcpp::Parameter> & parameters) = 0;
  std::weak_ptr<nav2::LifecycleNode> node_;
  rclcpp::Logger logger_;
  std::mutex mutex_;
  ParamsT params_;
  rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr on_set_;
  rclcpp::node_interfaces::PostSetParametersCallbackHandle::SharedPtr post_set_;
};
}  // namespace nav2_util
#endif
