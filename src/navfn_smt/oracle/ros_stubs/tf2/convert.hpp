// navfn-smt: see tf2/transform_stubs.hpp.
#pragma once
#include "tf2/transform_stubs.hpp"
