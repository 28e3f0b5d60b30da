// navfn-smt: builtin_interfaces/Duration and Time, for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_BUILTIN_INTERFACES_HPP_
#define NAVFN_SMT_PLUGIN_STUB_BUILTIN_INTERFACES_HPP_
#include <cstdint>
#include "rclcpp/rclcpp.hpp"
namespace builtin_interfaces
{
namespace msg
{
struct Duration
{
  int32_t sec = 0;
  uint32_t nanosec = 0;
};
struct Time
{
  int32_t sec = 0;
  uint32_t nanosec = 0;
  Time() = default;
  Time(const rclcpp::Time &) {}  // NOLINT: stamps are not compared
};
}  // namespace msg
}  // namespace builtin_interfaces
#endif
