// navfn-smt: geometry_msgs/Point32 (float32 coordinates), for the oracle build.
#ifndef NAVFN_SMT_STUB_POINT32_HPP_
#define NAVFN_SMT_STUB_POINT32_HPP_
namespace geometry_msgs
{
namespace msg
{
struct Point32
{
  float x = 0.0f, y = 0.0f, z = 0.0f;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
