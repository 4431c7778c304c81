-- The Cornell box's geometry, materials and camera, exactly as specified in ../shared/scenes/cornell-box-spec.md
-- (measured data from the Cornell Program of Computer Graphics); units are millimetres, +x points to the image's
-- left. Used by scenes/cornell-box.lua and bench/igi_convergence.lua:
--   local scene, camera = dofile(dir .. "/lib/cornell-box.lua")(torte)
return function(torte)
  local white = torte.material.matte{color = {0.73, 0.73, 0.73}}
  local red = torte.material.matte{color = {0.63, 0.065, 0.05}}
  local green = torte.material.matte{color = {0.14, 0.45, 0.091}}
  local black = torte.material.matte{color = 0}

  local scene = torte.scene()

  -- Every quad (v0, v1, v2, v3) is the two triangles (v0, v1, v2) and (v0, v2, v3): the red wall is not planar,
  -- so the split matters and is spelled out here rather than left to a polygon triangulator.
  local function quad(material, v0, v1, v2, v3, extra)
    local shape = {
      positions = {v0, v1, v2, v3},
      indices = {0, 1, 2, 0, 2, 3},
      material = material,
    }
    for k, v in pairs(extra or {}) do shape[k] = v end
    scene:add(torte.shape.mesh(shape))
  end

  quad(white, {552.8, 0, 0}, {0, 0, 0}, {0, 0, 559.2}, {549.6, 0, 559.2})                  -- floor
  quad(white, {556, 548.8, 0}, {556, 548.8, 559.2}, {0, 548.8, 559.2}, {0, 548.8, 0})      -- ceiling
  quad(white, {549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2})    -- back wall
  quad(green, {0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2})                  -- right wall
  quad(red, {552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0})        -- left wall

  -- Short block
  quad(white, {130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114})
  quad(white, {290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272})
  quad(white, {130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114})
  quad(white, {82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65})
  quad(white, {240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225})

  -- Tall block
  quad(white, {423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406})
  quad(white, {423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406})
  quad(white, {472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456})
  quad(white, {314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296})
  quad(white, {265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247})

  -- Light: emits only downwards (its winding gives the normal -y), 0.1 mm below the ceiling, albedo 0.
  quad(black, {343, 548.7, 227}, {343, 548.7, 332}, {213, 548.7, 332}, {213, 548.7, 227}, {emission = {17, 12, 4}})

  local camera = torte.camera.perspective{
    eye = {278, 273, -800}, look_at = {278, 273, 0}, up = {0, 1, 0},
    fov = 2 * math.deg(math.atan(12.5 / 35)), fov_axis = "vertical",
  }

  return scene, camera
end
