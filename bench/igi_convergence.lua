-- Issue 23's acceptance on IGI: with its default settings igi converges on the Cornell box. Renders the box
-- (scenes/lib/cornell-box.lua, as scenes/cornell-box.lua) with `path` at ref_spp as the reference and with `igi` at 8, 64
-- and 256 spp, then igi at 256 spp with a loose clamp (g_limit = loose_g_limit), and prints:
--   * the error of igi at 8 and 64 spp against the reference and its ratio (acceptance: <= 0.6). The metric is
--     the median over pixels of |igi - ref| in luminance, relative to the reference's mean luminance: the median
--     measures the noise of a typical pixel and ignores the few pixels where the clamp's bias (corners) or a VPL
--     spike sits, which an RMS would let dominate. For comparison the RMS of the 8x8 tile means is printed too:
--     tile means average the noise away, so it shows the clamp's bias floor instead;
--   * at 256 spp, per tile x tile tile the relative difference of igi's mean luminance from path's, the worst
--     tile and how many are within 3 % (acceptance: all), for the default clamp and the loose one.
--
--   nice torte --quiet bench/igi_convergence.lua [size=128] [ref_spp=4096] [tile=32] [loose_g_limit=10000]
--                                                [seed=0]
local torte = require "torte"

local opt = torte.options{size = 128, ref_spp = 4096, tile = 32, loose_g_limit = 1e4, seed = 0}

local script_dir = (debug.getinfo(1, "S").source:match("^@(.*)[/\\]") or ".")
local scene, camera = dofile(script_dir .. "/../scenes/lib/cornell-box.lua")(torte)

local n = opt.size
assert(n % opt.tile == 0 and n % 8 == 0, "size must be a multiple of tile and of 8")

-- Renders and returns the image's luminance as a flat array (row-major), with the render time.
local function render(integrator, spp, extra)
  local args = {scene = scene, camera = camera, width = n, height = n, spp = spp, integrator = integrator,
                seed = opt.seed, filter = torte.filter.box{radius = 0.5}}
  for k, v in pairs(extra or {}) do args[k] = v end
  local t0 = os.clock()
  local image = torte.render(args)
  local y = {}
  for py = 0, n - 1 do
    for px = 0, n - 1 do
      local r, g, b = image:pixel(px, py)
      y[py * n + px + 1] = 0.2126 * r + 0.7152 * g + 0.0722 * b
    end
  end
  return y, os.clock() - t0
end

local function mean(y)
  local s = 0
  for i = 1, #y do s = s + y[i] end
  return s / #y
end

-- Means of the t x t tiles, row-major.
local function tile_means(y, t)
  local out = {}
  for ty = 0, n // t - 1 do
    for tx = 0, n // t - 1 do
      local s = 0
      for py = ty * t, ty * t + t - 1 do
        for px = tx * t, tx * t + t - 1 do s = s + y[py * n + px + 1] end
      end
      out[#out + 1] = s / (t * t)
    end
  end
  return out
end

-- Median over pixels of |a - ref|, relative to ref's mean.
local function median_error(a, ref)
  local d = {}
  for i = 1, #a do d[i] = math.abs(a[i] - ref[i]) end
  table.sort(d)
  local m = #d // 2
  return (#d % 2 == 1 and d[m + 1] or 0.5 * (d[m] + d[m + 1])) / mean(ref)
end

-- RMS over 8x8 tiles of the difference of tile means, relative to ref's mean.
local function tile_rms_error(a, ref)
  local ta, tr = tile_means(a, 8), tile_means(ref, 8)
  local s = 0
  for i = 1, #ta do s = s + (ta[i] - tr[i]) ^ 2 end
  return math.sqrt(s / #ta) / mean(ref)
end

-- Relative differences of the tile x tile tile means; prints them as a grid, the worst and the count within 3 %.
local function tile_report(label, a, ref)
  local ta, tr = tile_means(a, opt.tile), tile_means(ref, opt.tile)
  local per_row = n // opt.tile
  local worst, worst_at, within = 0, 0, 0
  print(("%s: igi mean %.5f, path mean %.5f (%+.2f %%); tile means relative to path (%%, top row first):")
        :format(label, mean(a), mean(ref), 100 * (mean(a) / mean(ref) - 1)))
  for row = 0, per_row - 1 do
    local cells = {}
    for col = 0, per_row - 1 do
      local i = row * per_row + col + 1
      local rel = ta[i] / tr[i] - 1
      if math.abs(rel) > math.abs(worst) then worst, worst_at = rel, i end
      if math.abs(rel) <= 0.03 then within = within + 1 end
      cells[#cells + 1] = ("%+6.2f"):format(100 * rel)
    end
    print("    " .. table.concat(cells, " "))
  end
  print(("  worst tile %+.2f %% (row %d, column %d), %d of %d tiles within 3 %%")
        :format(100 * worst, (worst_at - 1) // per_row, (worst_at - 1) % per_row, within, #ta))
end

print(("igi convergence on the Cornell box, %dx%d, path reference at %d spp (seed %d), igi seed %d")
      :format(n, n, opt.ref_spp, opt.seed + 1, opt.seed))
-- Another seed than igi's, so that the reference does not share igi's camera samples (correlated pixel noise).
local ref, t_ref = render("path", opt.ref_spp, {seed = opt.seed + 1})
print(("path %d spp: mean luminance %.5f (%.0f s CPU)"):format(opt.ref_spp, mean(ref), t_ref))
local errors = {}
for _, spp in ipairs{8, 64} do
  local y, t = render("igi", spp)
  errors[spp] = median_error(y, ref)
  print(("igi %3d spp: median pixel error %.4f, 8x8 tile-mean RMS error %.4f (relative to the mean; %.0f s CPU)")
        :format(spp, errors[spp], tile_rms_error(y, ref), t))
end
print(("ratio of median pixel errors, 64 spp / 8 spp: %.3f (acceptance <= 0.6)"):format(errors[64] / errors[8]))
local igi256, t256 = render("igi", 256)
print(("igi 256 spp: median pixel error %.4f, 8x8 tile-mean RMS error %.4f (%.0f s CPU)")
      :format(median_error(igi256, ref), tile_rms_error(igi256, ref), t256))
tile_report("igi 256 spp, defaults (g_limit 20)", igi256, ref)
local loose, t_loose = render("igi", 256, {g_limit = opt.loose_g_limit})
print(("igi 256 spp, g_limit %g: median pixel error %.4f, 8x8 tile-mean RMS error %.4f (%.0f s CPU)")
      :format(opt.loose_g_limit, median_error(loose, ref), tile_rms_error(loose, ref), t_loose))
tile_report(("igi 256 spp, g_limit %g"):format(opt.loose_g_limit), loose, ref)
