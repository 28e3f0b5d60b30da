// navfn-smt: Humble's name of tf2/convert.hpp.
#pragma once
#include "tf2/convert.hpp"
