// navfn-smt: this machine's Eigen square root, as Rolling's InflationLayer takes it
// (distance_transform.hpp: img = img.cwiseSqrt() on a row-major float matrix), compiled with the
// layers' flags.  Reads int32 n, then n float32 values (n == 0 ends); answers their n square roots.
#include <Eigen/Core>
#include <cstdint>
#include <cstdio>

int main()
{
  for (;;) {
    int32_t n = 0;
    if (fread(&n, 4, 1, stdin) != 1 || n <= 0) {return 0;}
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> img(1, n);
    if (fread(img.data(), 4, n, stdin) != static_cast<size_t>(n)) {return 1;}
    img = img.cwiseSqrt();
    fwrite(img.data(), 4, n, stdout);
    fflush(stdout);
  }
}
