// navfn-smt: the node and transform-buffer types the plugin and the layers take: Rolling's
// nav2 types (NAVFN_SMT_NAV2_NODE) or the rclcpp_lifecycle and tf2_ros ones before.
#ifndef NAVFN_SMT_NODE_TYPES_HPP_
#define NAVFN_SMT_NODE_TYPES_HPP_
#ifdef NAVFN_SMT_NAV2_NODE
#include "nav2_ros_common/lifecycle_node.hpp"
#include "nav2_ros_common/tf2_factories.hpp"
using Node = nav2::LifecycleNode;
using TfBuffer = nav2::TransformBuffer;
#else
#include "rclcpp_lifecycle/lifecycle_node.hpp"
#include "tf2_ros/buffer.h"
using Node = rclcpp_lifecycle::LifecycleNode;
using TfBuffer = tf2_ros::Buffer;
#endif
#endif  // NAVFN_SMT_NODE_TYPES_HPP_
