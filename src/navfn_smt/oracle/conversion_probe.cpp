// navfn-smt: how this build's target converts a float to int where C++ leaves it undefined
// (NaN, infinities, values outside the int range), as navfn.cpp's (int) casts do.  Reads
// int32 n, then n float32 values; answers static_cast<int> of each as int32.  The values come
// from stdin, so the compiler cannot fold the conversions.
#include <cstdint>
#include <cstdio>

int main()
{
  int32_t n = 0;
  if (fread(&n, 4, 1, stdin) != 1 || n <= 0 || n > 64) {return 1;}
  float in[64];
  int32_t out[64];
  if (fread(in, 4, n, stdin) != static_cast<size_t>(n)) {return 1;}
  for (int32_t i = 0; i < n; i++) {
    out[i] = static_cast<int>(in[i]);
  }
  fwrite(out, 4, n, stdout);
  return 0;
}
