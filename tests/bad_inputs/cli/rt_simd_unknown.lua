-- expect: --simd: unknown SIMD target 'altivec' (known: auto, avx512, avx2, sse4, ssse3, scalar)
-- flags: --simd altivec
-- where: see 'torte --help'
-- A command-line error: the script never runs.
error('the script ran')
