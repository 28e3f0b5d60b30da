// navfn-smt: the names of rclcpp that Nav2's planner plugin uses, written for the oracle build
// (no ROS installation).  WARN and ERROR lines are formatted as rclcpp formats them (printf)
// and kept, in order, for the driver to report; DEBUG and INFO go nowhere.  Nothing here
// computes anything the plugin's results depend on.
#ifndef NAVFN_SMT_PLUGIN_STUB_RCLCPP_HPP_
#define NAVFN_SMT_PLUGIN_STUB_RCLCPP_HPP_

#include <atomic>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace navfn_smt
{
// (level, line): 30 WARN, 40 ERROR, as rcutils numbers them
inline std::vector<std::pair<int, std::string>> & log_lines()
{
  static std::vector<std::pair<int, std::string>> lines;
  return lines;
}
inline void log(int level, const char * fmt, ...)
{
  char buf[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof(buf), fmt, ap);
  va_end(ap);
  log_lines().emplace_back(level, buf);
}
}  // namespace navfn_smt

namespace rcl_interfaces
{
namespace msg
{
struct ParameterType
{
  enum : uint8_t {PARAMETER_NOT_SET = 0, PARAMETER_BOOL = 1, PARAMETER_INTEGER = 2, PARAMETER_DOUBLE = 3,
    PARAMETER_STRING = 4};
};
struct SetParametersResult
{
  bool successful = false;
  std::string reason;
};
}  // namespace msg
}  // namespace rcl_interfaces

namespace rclcpp
{
enum ParameterType : uint8_t
{
  PARAMETER_NOT_SET = 0, PARAMETER_BOOL = 1, PARAMETER_INTEGER = 2, PARAMETER_DOUBLE = 3, PARAMETER_STRING = 4
};

struct Logger
{
  std::string name;
};
inline Logger get_logger(const std::string & name) {return Logger{name};}

struct Time
{
  int64_t nanoseconds = 0;
};
struct Duration
{
  int64_t nanoseconds = 0;
  Duration() = default;
  Duration(int32_t seconds, uint32_t nanos) : nanoseconds(int64_t(seconds) * 1000000000 + nanos) {}
  static Duration from_seconds(double s) {Duration d; d.nanoseconds = static_cast<int64_t>(s * 1e9); return d;}
  double seconds() const {return nanoseconds * 1e-9;}
};
enum rcl_clock_type_t {RCL_ROS_TIME = 1, RCL_SYSTEM_TIME = 2, RCL_STEADY_TIME = 3};
}  // namespace rclcpp
using rclcpp::RCL_ROS_TIME;
namespace rclcpp
{
class Clock
{
public:
  using SharedPtr = std::shared_ptr<Clock>;
  explicit Clock(rcl_clock_type_t = RCL_ROS_TIME) {}
  Time now() const {return Time{};}  // stamps are not compared
};

// A parameter value of one of the types the plugin declares (bool, int, double, string).
class ParameterValue
{
public:
  ParameterValue() = default;
  explicit ParameterValue(bool v) : type_(rcl_interfaces::msg::ParameterType::PARAMETER_BOOL), b_(v) {}
  explicit ParameterValue(int v) : type_(rcl_interfaces::msg::ParameterType::PARAMETER_INTEGER), i_(v) {}
  explicit ParameterValue(int64_t v) : type_(rcl_interfaces::msg::ParameterType::PARAMETER_INTEGER), i_(v) {}
  explicit ParameterValue(double v) : type_(rcl_interfaces::msg::ParameterType::PARAMETER_DOUBLE), d_(v) {}
  explicit ParameterValue(const std::string & v)
  : type_(rcl_interfaces::msg::ParameterType::PARAMETER_STRING), s_(v) {}
  explicit ParameterValue(const char * v)
  : type_(rcl_interfaces::msg::ParameterType::PARAMETER_STRING), s_(v) {}
  uint8_t get_type() const {return type_;}
  bool as_bool() const {check(rcl_interfaces::msg::ParameterType::PARAMETER_BOOL); return b_;}
  int64_t as_int() const {check(rcl_interfaces::msg::ParameterType::PARAMETER_INTEGER); return i_;}
  double as_double() const {check(rcl_interfaces::msg::ParameterType::PARAMETER_DOUBLE); return d_;}
  const std::string & as_string() const {check(rcl_interfaces::msg::ParameterType::PARAMETER_STRING); return s_;}
  // as rclcpp's get<T>: a bool, any integer type (cast from the int64), a float or double
  // (cast from the double), a string
  template<typename T>
  T get() const
  {
    if constexpr (std::is_same_v<T, bool>) {
      return as_bool();
    } else if constexpr (std::is_integral_v<T>) {
      return static_cast<T>(as_int());
    } else if constexpr (std::is_floating_point_v<T>) {
      return static_cast<T>(as_double());
    } else {
      return as_string();
    }
  }

private:
  void check(uint8_t t) const
  {
    if (t != type_) {throw std::runtime_error("parameter of another type");}
  }
  uint8_t type_ = rcl_interfaces::msg::ParameterType::PARAMETER_NOT_SET;
  bool b_ = false;
  int64_t i_ = 0;
  double d_ = 0.0;
  std::string s_;
};
class Parameter
{
public:
  Parameter() = default;
  Parameter(const std::string & name, const ParameterValue & value) : name_(name), value_(value) {}
  // a value of a parameter type, as rclcpp::Parameter("test.tolerance", 1.0) in Nav2's tests
  template<typename T, typename = std::enable_if_t<!std::is_same_v<std::decay_t<T>, ParameterValue>>>
  Parameter(const std::string & name, T && value) : name_(name), value_(ParameterValue(std::forward<T>(value))) {}
  const std::string & get_name() const {return name_;}
  uint8_t get_type() const {return value_.get_type();}
  bool as_bool() const {return value_.as_bool();}
  int64_t as_int() const {return value_.as_int();}
  double as_double() const {return value_.as_double();}
  const ParameterValue & get_parameter_value() const {return value_;}

private:
  std::string name_;
  ParameterValue value_;
};

// A subscription's quality of service: kept, never used (the oracle delivers messages itself).
class QoS
{
public:
  explicit QoS(size_t depth = 10) : depth_(depth) {}
  QoS & transient_local() {return *this;}
  QoS & reliable() {return *this;}
  QoS & best_effort() {return *this;}
  QoS & keep_last(size_t depth) {depth_ = depth; return *this;}

private:
  size_t depth_;
};
struct SystemDefaultsQoS : QoS {};
struct CallbackGroup
{
  using SharedPtr = std::shared_ptr<CallbackGroup>;
};
template<typename MessageT>
struct Subscription
{
  using SharedPtr = std::shared_ptr<Subscription>;
};
struct SubscriptionOptions
{
  CallbackGroup::SharedPtr callback_group;
};

namespace node_interfaces
{
struct OnSetParametersCallbackHandle
{
  using SharedPtr = std::shared_ptr<OnSetParametersCallbackHandle>;
  using OnParametersSetCallbackType =
    std::function<rcl_interfaces::msg::SetParametersResult(const std::vector<rclcpp::Parameter> &)>;
  OnParametersSetCallbackType callback;
};
struct PostSetParametersCallbackHandle
{
  using SharedPtr = std::shared_ptr<PostSetParametersCallbackHandle>;
  using PostSetParametersCallbackType = std::function<void(const std::vector<rclcpp::Parameter> &)>;
  PostSetParametersCallbackType callback;
};
}  // namespace node_interfaces

// The process of Nav2's own tests (nav2_navfn_planner/test): init and shutdown have nothing
// to start; a parameter request is answered when it is made, so its future is ready when
// spun (the node's parameters: rclcpp_lifecycle/lifecycle_node.hpp).
inline void init(int, char **) {}
inline bool shutdown() {return true;}
enum class FutureReturnCode {SUCCESS, INTERRUPTED, TIMEOUT};
template<typename NodeT, typename FutureT>
FutureReturnCode spin_until_future_complete(const NodeT &, const FutureT & future)
{
  future.wait();
  return FutureReturnCode::SUCCESS;
}
}  // namespace rclcpp

#define RCLCPP_DEBUG(logger, ...) do {(void)(logger);} while (0)
#define RCLCPP_INFO(logger, ...) do {(void)(logger);} while (0)
#define RCLCPP_WARN(logger, ...) ::navfn_smt::log(30, __VA_ARGS__)
#define RCLCPP_ERROR(logger, ...) ::navfn_smt::log(40, __VA_ARGS__)
#define RCLCPP_FATAL(logger, ...) ::navfn_smt::log(50, __VA_ARGS__)
#define RCLCPP_DEBUG_ONCE(logger, ...) RCLCPP_DEBUG(logger, __VA_ARGS__)
#define RCLCPP_INFO_ONCE(logger, ...) RCLCPP_INFO(logger, __VA_ARGS__)
#define RCLCPP_WARN_ONCE(logger, ...) RCLCPP_WARN(logger, __VA_ARGS__)
#define RCLCPP_ERROR_ONCE(logger, ...) RCLCPP_ERROR(logger, __VA_ARGS__)
#define RCLCPP_DEBUG_EXPRESSION(logger, expr, ...) do {if (expr) {RCLCPP_DEBUG(logger, __VA_ARGS__);}} while (0)
#define RCLCPP_INFO_EXPRESSION(logger, expr, ...) do {if (expr) {RCLCPP_INFO(logger, __VA_ARGS__);}} while (0)
#define RCLCPP_WARN_EXPRESSION(logger, expr, ...) do {if (expr) {RCLCPP_WARN(logger, __VA_ARGS__);}} while (0)
#define RCLCPP_ERROR_EXPRESSION(logger, expr, ...) do {if (expr) {RCLCPP_ERROR(logger, __VA_ARGS__);}} while (0)
#define RCLCPP_FATAL_EXPRESSION(logger, expr, ...) do {if (expr) {RCLCPP_FATAL(logger, __VA_ARGS__);}} while (0)
#define RCLCPP_WARN_THROTTLE(logger, clock, ms, ...) RCLCPP_WARN(logger, __VA_ARGS__)
#define RCLCPP_ERROR_THROTTLE(logger, clock, ms, ...) RCLCPP_ERROR(logger, __VA_ARGS__)
#define RCLCPP_INFO_THROTTLE(logger, clock, ms, ...) RCLCPP_INFO(logger, __VA_ARGS__)
#define RCLCPP_DEBUG_THROTTLE(logger, clock, ms, ...) RCLCPP_DEBUG(logger, __VA_ARGS__)

#endif  // NAVFN_SMT_PLUGIN_STUB_RCLCPP_HPP_
