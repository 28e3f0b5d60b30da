// navfn-smt: which hypot kernel the build's C library computes with (the costmap's footprint
// radii call hypot(double, double)).  Reads int32 n, then n pairs of doubles; answers
// std::hypot of each pair as a double.  The values come from stdin, so the compiler cannot
// fold the calls.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

int main()
{
  int32_t n = 0;
  if (fread(&n, 4, 1, stdin) != 1 || n <= 0 || n > (1 << 20)) {return 1;}
  std::vector<double> in(2 * static_cast<size_t>(n)), out(static_cast<size_t>(n));
  if (fread(in.data(), 8, in.size(), stdin) != in.size()) {return 1;}
  for (int32_t i = 0; i < n; i++) {
    out[i] = std::hypot(in[2 * i], in[2 * i + 1]);
  }
  fwrite(out.data(), 8, out.size(), stdout);
  return 0;
}
