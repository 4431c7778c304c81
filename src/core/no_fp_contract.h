// Include first in a source file whose floating-point expressions must round operation by operation, as written:
// no contraction of a * b + c into one fused multiply-add (GCC contracts by default in C++ as soon as the target
// has FMA, and Highway's AVX2 and AVX-512 targets have it). The pragma applies to every function defined after
// it in the translation unit, including the inlined Highway functions of headers included later, so it must come
// before every other include. Each including file says why it needs exact roundings.
#pragma once

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif
