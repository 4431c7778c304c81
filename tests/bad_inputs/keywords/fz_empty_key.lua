-- expect: torte.shape.sphere: unknown key '' (accepted keys:
-- The empty key was silently accepted (it doubled as "no unknown key"); found by fuzz/fuzz_kwargs.cc.
torte.shape.sphere{[""] = 1}
