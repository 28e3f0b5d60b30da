// navfn-smt: a lifecycle node holding parameters, for the oracle build (no ROS installation).
// The driver sets the overrides a params file would give; declare_parameter returns the
// override when there is one (of the declared type, as rclcpp demands), else the default.
// A parameter request (set_parameters_atomically, as rclcpp's parameter service answers it):
// every parameter declared and of its declared type, then the set callbacks, the last added
// first, each able to refuse the whole request; only then the values change and the post-set
// callbacks run.
#ifndef NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_
#define NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeindex>
#include <vector>

#include "rclcpp/rclcpp.hpp"

namespace rclcpp_lifecycle
{
class LifecycleNode;
struct State {};  // a lifecycle transition's state, as the tests pass it to on_configure
}  // namespace rclcpp_lifecycle

namespace rclcpp
{
namespace node_interfaces
{
// each interface a parameter client is made of names the node it was taken from
struct NodeInterface
{
  rclcpp_lifecycle::LifecycleNode * node;
};
using NodeBaseInterface = NodeInterface;
}  // namespace node_interfaces
}  // namespace rclcpp

namespace rclcpp_lifecycle
{
class LifecycleNode
{
public:
  using SharedPtr = std::shared_ptr<LifecycleNode>;
  using WeakPtr = std::weak_ptr<LifecycleNode>;
  explicit LifecycleNode(const std::string & name = "global_costmap") : name_(name) {}
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
  // declared by type alone: it takes the override of that type, else stays unset
  void declare_parameter(const std::string & name, rclcpp::ParameterType type)
  {
    auto it = overrides.find(name);
    if (it != overrides.end() && it->second.get_type() == type) {params_[name] = it->second;}
  }
  template<typename T>
  bool get_parameter(const std::string & name, T & out) const
  {
    auto it = params_.find(name);
    if (it == params_.end()) {return false;}
    try {
      out = it->second.get<T>();
    } catch (const std::runtime_error &) {
      throw std::runtime_error("parameter " + name + " read as another type than declared");
    }
    return true;
  }
  rclcpp::Parameter get_parameter(const std::string & name) const
  {
    return rclcpp::Parameter(name, params_.at(name));
  }
  rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr add_on_set_parameters_callback(
    rclcpp::node_interfaces::OnSetParametersCallbackHandle::OnParametersSetCallbackType callback)
  {
    auto handle = std::make_shared<rclcpp::node_interfaces::OnSetParametersCallbackHandle>();
    handle->callback = callback;
    on_set_.insert(on_set_.begin(), handle);
    return handle;
  }
  void remove_on_set_parameters_callback(const rclcpp::node_interfaces::OnSetParametersCallbackHandle * handle)
  {
    for (auto it = on_set_.begin(); it != on_set_.end(); ++it) {
      if (it->get() == handle) {on_set_.erase(it); return;}
    }
  }
  template<typename CallbackT>
  rclcpp::node_interfaces::PostSetParametersCallbackHandle::SharedPtr add_post_set_parameters_callback(
    CallbackT callback)
  {
    auto handle = std::make_shared<rclcpp::node_interfaces::PostSetParametersCallbackHandle>();
    handle->callback = callback;
    post_set_.insert(post_set_.begin(), handle);
    return handle;
  }
  void remove_post_set_parameters_callback(const rclcpp::node_interfaces::PostSetParametersCallbackHandle * handle)
  {
    for (auto it = post_set_.begin(); it != post_set_.end(); ++it) {
      if (it->get() == handle) {post_set_.erase(it); return;}
    }
  }
  rcl_interfaces::msg::SetParametersResult set_parameters_atomically(const std::vector<rclcpp::Parameter> & parameters)
  {
    rcl_interfaces::msg::SetParametersResult result;
    for (const auto & p : parameters) {
      auto it = params_.find(p.get_name());
      if (it == params_.end()) {
        result.reason = "parameter " + p.get_name() + " is not declared";
        return result;
      }
      if (it->second.get_type() != p.get_type()) {
        result.reason = "parameter " + p.get_name() + " set to another type than declared";
        return result;
      }
    }
    result.successful = true;
    for (const auto & handle : std::vector<decltype(on_set_)::value_type>(on_set_)) {
      result = handle->callback(parameters);
      if (!result.successful) {return result;}
    }
    for (const auto & p : parameters) {params_[p.get_name()] = p.get_parameter_value();}
    for (const auto & handle : std::vector<decltype(post_set_)::value_type>(post_set_)) {
      handle->callback(parameters);
    }
    return result;
  }
  rclcpp::node_interfaces::NodeInterface * get_node_base_interface() {return &self_;}
  rclcpp::node_interfaces::NodeInterface * get_node_topics_interface() {return &self_;}
  rclcpp::node_interfaces::NodeInterface * get_node_graph_interface() {return &self_;}
  rclcpp::node_interfaces::NodeInterface * get_node_services_interface() {return &self_;}
  const char * get_namespace() const {return "/";}
  const char * get_name() const {return name_.c_str();}

  // Subscriptions: the callback is kept under its topic; the driver delivers a message to it
  // as a publisher would (``deliver``).
  template<typename MessageT, typename... Args>
  typename rclcpp::Subscription<MessageT>::SharedPtr create_subscription(const std::string & topic, Args && ... args)
  {
    // the callback is whichever argument takes the message: (topic, callback[, qos]) from
    // Jazzy on, (topic, qos, callback) before
    std::function<void(std::shared_ptr<MessageT>)> f;
    auto take = [&f](auto && a) {
        if constexpr (std::is_invocable_v<decltype(a), std::shared_ptr<MessageT>>) {
          if (!f) {f = a;}
        }
      };
    (take(args), ...);
    subscribers_.push_back({topic, typeid(MessageT), [f](const void * msg) {
          f(std::make_shared<MessageT>(*static_cast<const MessageT *>(msg)));
        }});
    return std::make_shared<rclcpp::Subscription<MessageT>>();
  }
  // every subscription to messages of this type, whatever its topic (the layers resolve their
  // topic names against the node's namespace); the topics reached
  template<typename MessageT>
  std::vector<std::string> deliver(const MessageT & msg)
  {
    std::vector<std::string> topics;
    for (auto & sub : subscribers_) {
      if (sub.type == std::type_index(typeid(MessageT))) {
        sub.call(&msg);
        topics.push_back(sub.topic);
      }
    }
    return topics;
  }

protected:
  std::string name_;
  rclcpp::node_interfaces::NodeInterface self_{this};
  std::vector<rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr> on_set_;
  std::vector<rclcpp::node_interfaces::PostSetParametersCallbackHandle::SharedPtr> post_set_;
  std::map<std::string, rclcpp::ParameterValue> params_;
  struct Subscriber
  {
    std::string topic;
    std::type_index type;
    std::function<void(const void *)> call;
  };
  std::vector<Subscriber> subscribers_;
};
}  // namespace rclcpp_lifecycle

namespace rclcpp
{
// a client of a node's parameter service: its requests answered by the node at once
class AsyncParametersClient
{
public:
  using SharedPtr = std::shared_ptr<AsyncParametersClient>;
  template<typename... Interfaces>
  explicit AsyncParametersClient(node_interfaces::NodeInterface * base, Interfaces...) : node_(base->node) {}
  std::shared_future<rcl_interfaces::msg::SetParametersResult> set_parameters_atomically(
    const std::vector<Parameter> & parameters)
  {
    std::promise<rcl_interfaces::msg::SetParametersResult> answer;
    answer.set_value(node_->set_parameters_atomically(parameters));
    return answer.get_future().share();
  }

private:
  rclcpp_lifecycle::LifecycleNode * node_;
};
}  // namespace rclcpp

#endif  // NAVFN_SMT_PLUGIN_STUB_LIFECYCLE_NODE_HPP_
