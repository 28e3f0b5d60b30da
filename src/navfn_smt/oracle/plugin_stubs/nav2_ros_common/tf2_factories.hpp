// navfn-smt: the transform buffer type of nav2_ros_common (rolling); the plugin only keeps it.
#ifndef NAVFN_SMT_PLUGIN_STUB_TF2_FACTORIES_HPP_
#define NAVFN_SMT_PLUGIN_STUB_TF2_FACTORIES_HPP_
#include <memory>
namespace nav2
{
struct TransformBuffer
{
  using SharedPtr = std::shared_ptr<TransformBuffer>;
};
}
#endif
