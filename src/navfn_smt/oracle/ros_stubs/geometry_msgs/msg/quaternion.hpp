// navfn-smt: geometry_msgs/Quaternion (identity by default, compared member by member as the
// generated message's operators do), for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_QUATERNION_HPP_
#define NAVFN_SMT_PLUGIN_STUB_QUATERNION_HPP_
namespace geometry_msgs
{
namespace msg
{
struct Quaternion
{
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  bool operator==(const Quaternion & o) const {return x == o.x && y == o.y && z == o.z && w == o.w;}
  bool operator!=(const Quaternion & o) const {return !(*this == o);}
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
