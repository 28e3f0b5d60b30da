"""The constants of Nav2's NavFn (``navfn.hpp``), with the C++ types they carry, and the
few of the C++ library and of ``nav2_costmap_2d`` that the planner plugin and the costmap
layers around it use: each stated once, here.

Values that C++ writes as ``double`` literals stay Python floats here (they are
doubles); values that become ``float`` in the arithmetic are noted where they do.
"""

import sys

# Internal NavFn costs (COSTTYPE is unsigned char).
COST_UNKNOWN_ROS = 255  # ROS costmap "unknown"
COST_OBS = 254  # NavFn lethal obstacle
COST_OBS_ROS = 253  # ROS costmap "inscribed inflated obstacle"
COST_NEUTRAL = 50  # NavFn cost of open space
COST_FACTOR = 0.8  # double literal, used in setCostmap's translation

# Potential of a cell that propagation has not reached: the double literal 1.0e10,
# which is exactly representable in float32 (2**10 * 9765625).
POT_HIGH = 1.0e10

# Capacity of each of the three priority buffers; a push to a full buffer is dropped.
PRIORITYBUFSIZE = 10000

# Planar-wave update: the quadratic approximation's coefficients (double literals).
QUAD_A = -0.2301
QUAD_B = 0.5307
QUAD_C = 0.7040

# INVSQRT2 as NavFn defines it (a double literal, not 1/sqrt(2) to full precision).
INVSQRT2 = 0.707106781

# Default path step of calcPath, a float member (0.5 is exact in float32).
PATH_STEP = 0.5

# Priority threshold increment the Nav2 planner sets for both modes: 2 * COST_NEUTRAL (int).
PRI_INC = 2 * COST_NEUTRAL

# x86-64's cvttss2si/cvttsd2si result for NaN and out-of-range conversions to int32.
INT_MIN = -(2**31)
INT_MAX = 2**31 - 1

# <cfloat>'s DBL_MAX: getPointPotential's "no potential" and the tolerance search's first
# best_sdist in the planner plugin, DT_INF's double in the footprint's distances.
DBL_MAX = sys.float_info.max

# nav2_costmap_2d/cost_values.hpp: the costmap's values (unsigned char) that the layers write
# and the plugin hands to setCostmap (which knows 253 and 255 as COST_OBS_ROS and
# COST_UNKNOWN_ROS).
NO_INFORMATION = 255
LETHAL_OBSTACLE = 254
INSCRIBED_INFLATED_OBSTACLE = 253
FREE_SPACE = 0
