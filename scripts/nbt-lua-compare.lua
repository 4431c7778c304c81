-- Measures torte.data.nbt (C++) against an NBT decoder written in Lua (string.unpack), on every chunk of three
-- worlds in ../shared/data/minecraft:   build/torte scripts/nbt-lua-compare.lua
-- Result on 2026-11-22 (2 vCPU, busy machine): C++ is 3-6x faster (1.20.1: 0.10 s vs 0.34 s for 633 chunks,
-- 14.9 MB of NBT; 1.16: 0.05 s vs 0.30 s), so the loader uses the C++ decoder.
local unpack = string.unpack
local function nbt_lua(s)
  local read
  local function payload(t, p)
    if t == 1 then return unpack(">i1", s, p)
    elseif t == 2 then return unpack(">i2", s, p)
    elseif t == 3 then return unpack(">i4", s, p)
    elseif t == 4 then return unpack(">i8", s, p)
    elseif t == 5 then return unpack(">f", s, p)
    elseif t == 6 then return unpack(">d", s, p)
    elseif t == 7 then local n; n, p = unpack(">i4", s, p); return s:sub(p, p + n - 1), p + n
    elseif t == 8 then return unpack(">s2", s, p)
    elseif t == 9 then
      local et, n; et, n, p = unpack(">Bi4", s, p)
      local out = {}
      for i = 1, n do out[i], p = payload(et, p) end
      return out, p
    elseif t == 10 then
      local out = {}
      while true do
        local tt; tt, p = unpack("B", s, p)
        if tt == 0 then return out, p end
        local name; name, p = unpack(">s2", s, p)
        out[name], p = payload(tt, p)
      end
    elseif t == 11 or t == 12 then
      local n; n, p = unpack(">i4", s, p)
      local out = {}
      local f = t == 11 and ">i4" or ">i8"
      local w = t == 11 and 4 or 8
      -- batches of 64 via a single unpack
      local i = 1
      while i <= n do
        local k = math.min(64, n - i + 1)
        local vals = {unpack(">" .. (f:sub(2)):rep(k), s, p)}
        for j = 1, k do out[i + j - 1] = vals[j] end
        p = p + k * w; i = i + k
      end
      return out, p
    end
    error("bad tag " .. t)
  end
  local t, name, p = unpack(">Bs2", s, 1)
  return (payload(t, p))
end
local region = require "minecraft.region"
local script_dir = (debug.getinfo(1, "S").source:match("^@(.*)[/\\]") or ".")
local base = script_dir .. "/../../shared/data/minecraft/"
for _, w in ipairs{"bluenbt-1.20.1-paper", "prismarine-1.8.9", "prismarine-1.16"} do
  local files = require("minecraft.world").region_files(base .. w)
  local r = region.open(files[1])
  local raws = {}
  local t0 = torte.clock()
  for _, c in ipairs(r:chunks()) do
    local start = c.sector * 4096
    local len = string.unpack(">I4", r.bytes, start + 1)
    raws[#raws + 1] = torte.data.inflate(r.bytes:sub(start + 6, start + 4 + len))
  end
  local t1 = torte.clock()
  for _, s in ipairs(raws) do torte.data.nbt(s) end
  local t2 = torte.clock()
  for _, s in ipairs(raws) do nbt_lua(s) end
  local t3 = torte.clock()
  local bytes = 0; for _, s in ipairs(raws) do bytes = bytes + #s end
  print(("%s: %d chunks, %.1f MB NBT; inflate %.3f s, nbt C++ %.3f s, nbt Lua %.3f s (x%.1f)"):format(w, #raws, bytes/1e6, t1-t0, t2-t1, t3-t2, (t3-t2)/(t2-t1)))
end
