// navfn-smt: std_msgs/Header, for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_HEADER_HPP_
#define NAVFN_SMT_PLUGIN_STUB_HEADER_HPP_
#include <string>
#include "builtin_interfaces/msg/duration.hpp"
namespace std_msgs
{
namespace msg
{
struct Header
{
  builtin_interfaces::msg::Time stamp;
  std::string frame_id;
};
}  // namespace msg
}  // namespace std_msgs
#endif
