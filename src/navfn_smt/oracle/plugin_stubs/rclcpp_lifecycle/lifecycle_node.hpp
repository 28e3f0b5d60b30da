// navfn-smt: a lifecycle node holding parameters, for the oracle build (no ROS installation).
// The driver sets the overrides a params file would give; declare_parameter returns the
// override when there is one (of the declared type, as rclcpp demands), else the default.
#ifndef NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_
#define NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rclcpp/rclcpp.hpp"

namespace rclcpp_lifecycle
{
class LifecycleNode
{
public:
  using SharedPtr = std::shared_ptr<LifecycleNode>;
  using WeakPtr = std::weak_ptr<LifecycleNode>;
  virtual ~LifecycleNode() = default;

  std::map<std::string, rclcpp::ParameterValue> overrides;  // set by the driver

  rclcpp::Clock::SharedPtr get_clock() {return std::make_shared<rclcpp::Clock>();}
  rclcpp::Logger get_logger() const {return rclcpp::get_logger("planner_server");}
  bool has_parameter(const std::string & name) const {return params_.count(name) > 0;}
  const rclcpp::ParameterValue & declare_parameter(
    const std::string & name, const rclcpp::ParameterValue & default_value)
  {
    auto it = overrides.find(name);
    params_[name] = (it != overrides.end() && it->second.get_type() == default_value.get_type()) ?
      it->second : default_value;
    return params_[name];
  }
  template<typename T>
  bool get_parameter(const std::string & name, T & out) const
  {
    auto it = params_.find(name);
    if (it == params_.end()) {return false;}
    out = it->second.get<T>();
    return true;
  }
  rclcpp::Parameter get_parameter(const std::string & name) const
  {
    return rclcpp::Parameter(name, params_.at(name));
  }
  rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr add_on_set_parameters_callback(
    rclcpp::node_interfaces::OnSetParametersCallbackHandle::OnParametersSetCallbackType)
  {
    return std::make_shared<rclcpp::node_interfaces::OnSetParametersCallbackHandle>();
  }
  void remove_on_set_parameters_callback(const rclcpp::node_interfaces::OnSetParametersCallbackHandle *) {}

protected:
  std::map<std::string, rclcpp::ParameterValue> params_;
};
}  // namespace rclcpp_lifecycle

#endif  // NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_
