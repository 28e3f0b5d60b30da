// navfn-smt: the transform buffer type of nav2_ros_common (rolling): see tf2_ros/buffer.h.
#ifndef NAVFN_SMT_PLUGIN_STUB_TF2_FACTORIES_HPP_
#define NAVFN_SMT_PLUGIN_STUB_TF2_FACTORIES_HPP_
#include <memory>
#include "tf2_ros/buffer.h"
namespace nav2
{
struct TransformBuffer : tf2_ros::Buffer
{
  using SharedPtr = std::shared_ptr<TransformBuffer>;
};
// as nav2::create_transform_buffer(node) makes the buffer Nav2's tests pass to the plugin
template<typename NodeT>
TransformBuffer::SharedPtr create_transform_buffer(const NodeT &) {return std::make_shared<TransformBuffer>();}
}
#endif
