// navfn-smt: the tf2 names the static layer uses when its map lies in another frame than the
// costmap or the costmap rolls with the robot.  The oracle gives it neither (one frame, a
// static costmap): these are declared so the layer compiles, and any use stops the oracle.
#ifndef NAVFN_SMT_STUB_TF2_HPP_
#define NAVFN_SMT_STUB_TF2_HPP_
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include "geometry_msgs/msg/transform_stamped.hpp"
namespace tf2
{
using Duration = std::chrono::nanoseconds;
inline Duration durationFromSec(double s) {return Duration(static_cast<int64_t>(s * 1e9));}
struct TimePoint {};
static const TimePoint TimePointZero{};
struct TransformException : std::runtime_error
{
  using std::runtime_error::runtime_error;
};
struct Vector3
{
  Vector3(double, double, double) {}
  double x() const {std::abort();}
  double y() const {std::abort();}
};
struct Transform
{
  Vector3 operator*(const Vector3 &) const {std::abort();}
};
template<typename A, typename B>
void fromMsg(const A &, B &) {std::abort();}
}  // namespace tf2
#endif
