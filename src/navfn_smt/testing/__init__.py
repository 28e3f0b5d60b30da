"""What the tests share that needs the whole package: the conformance harness
(:mod:`.conformance`), which runs every numeric domain on the kernels' table."""
