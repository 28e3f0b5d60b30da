// navfn-smt: tf2_ros::Buffer (humble to kilted); the plugin only keeps a pointer to it.
#ifndef NAVFN_SMT_PLUGIN_STUB_TF2_BUFFER_H_
#define NAVFN_SMT_PLUGIN_STUB_TF2_BUFFER_H_
namespace tf2_ros
{
class Buffer {};
}
#endif
