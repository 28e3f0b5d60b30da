// navfn-smt: the few names of rclcpp that Nav2's NavFn core uses, written for the oracle build
// (no ROS installation).  Logging goes nowhere: the oracle compares computed values, not logs.
#ifndef NAVFN_SMT_STUB_RCLCPP_HPP_
#define NAVFN_SMT_STUB_RCLCPP_HPP_

namespace rclcpp
{
struct Logger {};
inline Logger get_logger(const char *) {return Logger{};}
}  // namespace rclcpp

#define RCLCPP_DEBUG(logger, ...) do {(void)(logger);} while (0)
#define RCLCPP_INFO(logger, ...) do {(void)(logger);} while (0)
#define RCLCPP_WARN(logger, ...) do {(void)(logger);} while (0)
#define RCLCPP_ERROR(logger, ...) do {(void)(logger);} while (0)

#endif  // NAVFN_SMT_STUB_RCLCPP_HPP_
