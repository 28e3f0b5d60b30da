// navfn-smt: tf2_ros::Buffer (humble to kilted): the plugin keeps a pointer to it; the static
// layer would look a transform up only for a map in another frame, which the oracle never gives.
#ifndef NAVFN_SMT_PLUGIN_STUB_TF2_BUFFER_H_
#define NAVFN_SMT_PLUGIN_STUB_TF2_BUFFER_H_
#include <cstdlib>
#include <string>
#include "tf2/transform_stubs.hpp"
namespace tf2_ros
{
class Buffer
{
public:
  Buffer() = default;
  template<typename ClockT>
  explicit Buffer(const ClockT &) {}  // a node's clock, as Nav2's tests make one
  template<typename... Args>
  geometry_msgs::msg::TransformStamped lookupTransform(Args && ...) const {std::abort();}
};
}
#endif
