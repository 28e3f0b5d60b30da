// navfn-smt: declared for costmap_2d.cpp (rolling), whose outline functions the plugin never
// calls; calling it stops the oracle rather than compute anything.
#ifndef NAVFN_SMT_PLUGIN_STUB_RAYTRACE_LINE_2D_HPP_
#define NAVFN_SMT_PLUGIN_STUB_RAYTRACE_LINE_2D_HPP_
#include <climits>
#include <cstdlib>
namespace nav2_util
{
template<class ActionType>
inline void raytraceLine(ActionType, unsigned int, unsigned int, unsigned int, unsigned int,
  unsigned int = UINT_MAX) {std::abort();}
}
#endif
