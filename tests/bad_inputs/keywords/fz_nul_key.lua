-- expect: torte.material.matte: unknown key '\x00' (accepted keys: color, sigma)
-- A key holding a NUL byte was silently accepted (KwArgs::finish compared C strings); found by fuzz/fuzz_kwargs.cc.
torte.material.matte{["\0"] = 1}
