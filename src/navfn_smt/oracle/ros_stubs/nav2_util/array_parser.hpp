// navfn-smt: nav2_util::parseVVF (Rolling), for footprint strings, which the oracle never gives
// (it passes the footprint as points): calling it stops the oracle.
#ifndef NAVFN_SMT_STUB_ARRAY_PARSER_HPP_
#define NAVFN_SMT_STUB_ARRAY_PARSER_HPP_
#include <cstdlib>
#include <string>
#include <vector>
namespace nav2_util
{
inline std::vector<std::vector<float>> parseVVF(const std::string &, std::string &) {std::abort();}
}
#endif
