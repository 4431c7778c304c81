-- expect: asked for 1.0 GB more; --lua-memory SIZE raises the limit
-- flags: --lua-memory 32M
local s = string.rep("x", 1 << 30)
