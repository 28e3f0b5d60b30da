// navfn-smt: nav2::qos (Rolling): subscriptions' quality of service, kept and never used.
#ifndef NAVFN_SMT_STUB_QOS_PROFILES_HPP_
#define NAVFN_SMT_STUB_QOS_PROFILES_HPP_
#include "rclcpp/rclcpp.hpp"
namespace nav2
{
namespace qos
{
struct StandardTopicQoS : rclcpp::QoS
{
  explicit StandardTopicQoS(int depth = 10) : rclcpp::QoS(depth) {}
};
struct LatchedSubscriptionQoS : rclcpp::QoS
{
  explicit LatchedSubscriptionQoS(int depth = 1) : rclcpp::QoS(depth) {}
};
}  // namespace qos
}  // namespace nav2
#endif
