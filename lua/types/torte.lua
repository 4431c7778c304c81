---@meta torte
-- Generated from docs/lua-api.md by tests/io/test_lua_api_doc.cc (make lua-stubs); do not edit.
-- Editors with the Lua language server (LuaLS) complete and check scene scripts with these stubs
-- (.luarc.json at the repository's root points at this directory).

---@class torte.data.longs
local torte_data_longs = {}
---@class torte.image
local torte_image = {}
---@class torte.mesh
local torte_mesh = {}
---@class torte.scene
local torte_scene = {}
---@class torte.texture
local torte_texture = {}
---@class torte.transform
local torte_transform = {}
---@class torte.voxel.grid
local torte_voxel_grid = {}

---@class torte
torte = {}
torte.camera = {}
torte.data = {}
torte.filter = {}
torte.gltf = {}
torte.light = {}
torte.material = {}
torte.mesh = {}
torte.shape = {}
torte.simd = {}
torte.texture = {}
torte.voxel = {}

---A new, empty scene (a `torte.scene` userdata with the methods `add`, `frame` and `stats`). The keys choose how its triangles are laid out for tracing: the default layout (8-wide nodes of float boxes, 6.8 bytes per triangle, and leaves that copy each triangle's vertices, 36), the packed one (the same nodes, and leaves that carry each leaf's distinct vertices once with 8-bit indices into them, about 19; a few percent slower to trace) or the compact one (packed leaves, and nodes whose child boxes are 8-bit offsets on a per-node grid, 3.4; up to about 20 % slower; `bench/RESULTS.md`, 2026-12-07). The summary after a render and `--stats` name the layout. `torte.render` takes the same keys for one render.
---@param args torte.scene.args
---@return torte.scene
function torte.scene(args) end

---A new, empty group: a `torte.scene` meant to be placed many times by `torte.instance{group = g}`. Groups share their geometry between placements and nest (at most 32 levels, unrolling to at most 2^28 instances and 2^20 lights). Point, spot and directional lights in a group are copied by each placement; emitting shapes and lights at infinity in an instanced group are refused at render time.
---@return torte.scene
function torte.group() end

---One placement of a group, to pass to `scene:add`. A group cannot contain an instance of itself, directly or through other groups (`scene:add` refuses it).
---@param args torte.instance.args
---@return torte.instance
function torte.instance(args) end

---Adds shapes, lights and instances (any number of arguments; arrays of them, nested up to 16 levels, are added element by element) and returns the scene, so calls chain. A `torte.scene`/group itself is refused: place it with `torte.instance` or `scene:frame`. Any `add`, to the scene or to a group it places, makes the next render rebuild the scene.
---@param obj any
---@param ... any
---@return torte.scene
function torte_scene:add(obj, ...) end

---Makes a new group, calls the function with it to fill it, places it in `scene` with `transform` (identity when omitted) and returns the group, to place it again with `torte.instance`. Frames nest: call `g:frame` inside. A frame whose group would place the scene it is framed in is an error.
---@param transform any
---@param function_ any
---@param g any
---@return torte.scene
function torte_scene:frame(transform, function_, g) end

---Flattens and builds the scene as `torte.render` would (the build is cached: a render of the unchanged scene reuses it) and returns its statistics: `primitives`, `triangles`, `instances`, `groups`, `placed_primitives`, `lights`, `layout` (the triangles' layout the build used: `"default"` or `"compact"`, see `torte.scene`), `nodes`, `leaves` and `depth` of the top-level triangle BVH, its `sah_cost` (expected node visits plus triangle tests of a random ray through the scene's bounds), `bytes_per_triangle = {nodes, leaves, indices, index_map, normals}`, `voxel_grids`, `voxel_nodes`, `voxels` (solid) and `voxel_bytes_per_voxel` of the top level's voxel grids, `bounds = {min = {x, y, z}, max = {x, y, z}}`, `geometry_bytes`, `accel_bytes`, `build_seconds`, `reused` (boolean) and `peak_memory` (bytes). Build errors are raised as `scene:stats: <message>`.
---@return table
function torte_scene:stats() end

---Builds the scene (or reuses the build of the unchanged scene of the previous render or `scene:stats()`), renders it with `camera` and returns a `torte.image`. Every integrator-specific key is accepted and range-checked with any integrator, and used only by its own.
---@param args torte.render.args
---@return torte.image
function torte.render(args) end

---Writes the image to `path` (relative to the working directory) in the format its extension names and returns the image. `.exr`: 32-bit float, linear, with the render's metadata and AOV layers; `.hdr`: RGBE; `.png`, `.jpg`, `.tif`, ...: 8 bits after `exposure` and the view transform (`docs/output.md`). `--exposure` and `--tonemap` on the command line override the options. In a distributed render only rank 0 writes.
---@param path any
---@param args image.write.args
---@return torte.image
function torte_image:write(path, args) end

---The linear RGB value of pixel (x, y), 0-based integers with (0, 0) at the top left. Coordinates outside the image are an error.
---@param x any
---@param y any
---@return any
function torte_image:pixel(x, y) end

---The mean linear RGB value over all pixels.
---@return any
function torte_image:mean() end

---A new image holding AOV layer `name` of the image (one of `image.layers`) as its pixels: a three-channel layer as R, G, B, a one-channel layer as grey. The new image has no layers. An unknown name is an error listing those there are.
---@param name any
---@return torte.image
function torte_image:layer(name) end

---A denoised copy of the image (an edge-avoiding à-trous filter guided by its `albedo`, `normal` and `depth` layers, which the image must hold: render with `aovs = {"albedo", "normal", "depth"}`, or use `denoise = true` on `torte.render` instead). Pixels an `emission` layer shows lit directly keep their values; a `variance` layer (each pixel's mean-luminance variance, which renders write with `denoise = true` or `aovs = {"variance"}`) keeps one-pixel glints whose samples agree, and a `glossiness` layer lets the normals of diffuse surfaces differ where glossy ones' must agree. The input is kept as layer `"noisy"`.
---@param image any
---@param args torte.denoise.args
---@return torte.image
function torte.denoise(image, args) end

---`image:write(path, options)`, plus a PNG preview beside `.exr` and `.hdr` outputs (same name, `.png` extension, same options). Errors are reported at the line that called `torte.save`. Defined in Lua by the prelude; the options table is `image:write`'s.
---@param image any
---@param path any
---@param args any
---@return torte.image
function torte.save(image, path, args) end

---A box of half-width `radius` pixels (the default filter of `torte.render`).
---@param args torte.filter.box.args
---@return torte.filter
function torte.filter.box(args) end

---A tent filter of half-width `radius` pixels.
---@param args torte.filter.triangle.args
---@return torte.filter
function torte.filter.triangle(args) end

---A Gaussian of standard deviation `sigma` pixels, truncated at `radius` and shifted to reach 0 there.
---@param args torte.filter.gaussian.args
---@return torte.filter
function torte.filter.gaussian(args) end

---The Mitchell-Netravali cubic with parameters B and C, scaled to half-width `radius`.
---@param args torte.filter.mitchell.args
---@return torte.filter
function torte.filter.mitchell(args) end

---A diffuse reflector: Lambert, or Oren-Nayar (the qualitative model) when `sigma` > 0.
---@param args torte.material.matte.args
---@return torte.material
function torte.material.matte(args) end

---Another name for `torte.material.matte`: the same function, keys and error messages (which say `torte.material.matte`).
---@param args any
---@return torte.material
function torte.material.lambert(args) end

---A diffuse base under a dielectric coating (Fresnel-weighted, energy-conserving); `roughness = 0` is a smooth, delta coating.
---@param args torte.material.plastic.args
---@return torte.material
function torte.material.plastic(args) end

---A conductor with exact complex-IOR Fresnel per channel (delta reflection when the roughness is 0). Give a preset name or `eta` and `k`, not both; with neither the metal is aluminium. Presets: `"gold"`/`"Au"`, `"silver"`/`"Ag"`, `"copper"`/`"Cu"`, `"aluminium"`/`"aluminum"`/`"Al"`, `"chromium"`/`"Cr"`, `"tungsten"`/`"W"`, `"nickel"`/`"Ni"`, `"vanadium"`/`"V"`, `"iridium"`/`"Ir"`, `"mercury"`/`"Hg"`. The `metal` key is read only when given, so the accepted-keys list of an error names it only then.
---@param args torte.material.metal.args
---@return torte.material
function torte.material.metal(args) end

---Perfect specular reflection, tinted by `color`.
---@param args torte.material.mirror.args
---@return torte.material
function torte.material.mirror(args) end

---A smooth dielectric (Fresnel reflection and refraction). `thin = true` models a thin slab: inter-reflections summed, transmitted rays pass straight through.
---@param args torte.material.glass.args
---@return torte.material
function torte.material.glass(args) end

---Microfacet reflection and transmission (Walter et al. 2007).
---@param args torte.material.rough_glass.args
---@return torte.material
function torte.material.rough_glass(args) end

---`a` where `amount` is 0, `b` where it is 1; in between each hit picks `b` with probability `amount` (unbiased for the blend). `mix` and `bump` nest at most 64 levels.
---@param args torte.material.mix.args
---@return torte.material
function torte.material.mix(args) end

---`material` with its shading normal perturbed by the height field `scale * height` along the normal (finite differences along dp/du and dp/dv; a constant `height` leaves the normal unchanged), or by a tangent-space `normal_map`: rgb = (n + 1) / 2 with +x along dp/du and +y along dp/dv (OpenGL's and glTF's convention), x and y times `scale`; (0.5, 0.5, 1) leaves the normal unchanged, a map pointing below the surface is ignored.
---@param args torte.material.bump.args
---@return torte.material
function torte.material.bump(args) end

---A cut-out: `material` where `alpha >= cutoff` and no surface at all elsewhere, for camera, extension and shadow rays alike (leaves, fences, glTF's alphaMode MASK). With `stochastic = true` the surface is present with probability `alpha` instead (glTF's BLEND: unbiased for the blend, no sorting), decided per hit. A masked material cannot be given to an emitting shape. Cut-out layers cost a ray an extra trace each (at most 64 are passed).
---@param args torte.material.mask.args
---@return torte.material
function torte.material.mask(args) end

---A constant: `float` for a number, `color` for `{r, g, b}`.
---@param args torte.texture.constant.args
---@return torte.texture
function torte.texture.constant(args) end

---none -> vec2: the surface uv times `scale` plus `offset`.
---@param args torte.texture.uv.args
---@return torte.texture
function torte.texture.uv(args) end

---none -> vec2: u = atan2(z, x) / 2pi in [0, 1), v = 1 - theta/pi with theta measured from +y, of the shading point in the mapping's space (`transform` places the mapping in the world like a shape transform).
---@param args torte.texture.spherical.args
---@return torte.texture
function torte.texture.spherical(args) end

---none -> vec2: u as `spherical`, v = y in the mapping's space.
---@param args torte.texture.cylindrical.args
---@return torte.texture
function torte.texture.cylindrical(args) end

---none -> vec2: (p . s + offset_u, p . t + offset_v) of the point p in the mapping's space.
---@param args torte.texture.planar.args
---@return torte.texture
function torte.texture.planar(args) end

---none -> vec3: the shading point in the mapping's space (the usual input of 3D noise and `checker3d`).
---@param args torte.texture.xyz.args
---@return torte.texture
function torte.texture.xyz(args) end

---vec2 -> float or color: `a` where floor(x * scale) + floor(y * scale) is even, else `b`. `a` and `b` may be textures themselves.
---@param args torte.texture.checker.args
---@return torte.texture
function torte.texture.checker(args) end

---vec3 -> float or color: `checker` over 3D cells.
---@param args torte.texture.checker3d.args
---@return torte.texture
function torte.texture.checker3d(args) end

---vec2 or vec3 -> float: value noise in [0, 1].
---@param args torte.texture.value_noise.args
---@return torte.texture
function torte.texture.value_noise(args) end

---vec2 or vec3 -> float: Perlin gradient noise mapped to [0, 1].
---@param args torte.texture.perlin.args
---@return torte.texture
function torte.texture.perlin(args) end

---Another name for `torte.texture.perlin`: the same function and keys (errors say `torte.texture.perlin`).
---@param args any
---@return torte.texture
function torte.texture.noise(args) end

---vec2 or vec3 -> float: fractional Brownian motion, a sum of `octaves` noise layers, normalised to [0, 1].
---@param args torte.texture.fbm.args
---@return torte.texture
function torte.texture.fbm(args) end

---vec2 or vec3 -> float: as `fbm` with the absolute value of each (signed) layer, in [0, 1].
---@param args torte.texture.turbulence.args
---@return torte.texture
function torte.texture.turbulence(args) end

---vec2 -> color: an image file read through OpenImageIO (any format it reads; MIP-mapped), uv (0, 0) at the image's bottom left. With `color_space = "auto"`, 8-bit images are sRGB-decoded unless the file says it is linear; other formats are taken as linear. The file is opened when the texture is made; a missing file is an error naming it.
---@param args torte.texture.image.args
---@return torte.texture
function torte.texture.image(args) end

---float -> color: r = g = b = x. It takes no keys: an empty table or none (any key is an error).
---@param args any
---@return torte.texture
function torte.texture.grayscale(args) end

---float -> color: a colour ramp through `colors` at `positions`.
---@param args torte.texture.spline.args
---@return torte.texture
function torte.texture.spline(args) end

---a + b pointwise (a `float` broadcasts to `color`); the same as `a + b`.
---@param args torte.texture.add.args
---@return torte.texture
function torte.texture.add(args) end

---a * b pointwise; the same as `a * b` for two textures.
---@param args torte.texture.multiply.args
---@return torte.texture
function torte.texture.multiply(args) end

---The texture times a constant factor (`texture * factor`); `texture` must have a scalar or colour output (an error about it calls the key `'a'`).
---@param args torte.texture.scale.args
---@return torte.texture
function torte.texture.scale(args) end

---(1 - t) * a + t * b, with `t` a scalar texture.
---@param args torte.texture.lerp.args
---@return torte.texture
function torte.texture.lerp(args) end

---The same as `torte.texture.lerp`, under its own name in errors.
---@param args torte.texture.mix.args
---@return torte.texture
function torte.texture.mix(args) end

---outer(inner(x)), the same as `outer .. inner`: `inner`'s output type must be `outer`'s input type.
---@param args torte.texture.compose.args
---@return torte.texture
function torte.texture.compose(args) end

---Evaluates the texture at a shading point: a number for `float` textures, else a table (`{r, g, b}`, `{x, y}` or `{x, y, z}`). Without `input` the texture is closed with its default input (uv for vec2, the position for vec3); with `input` (a number, `{x, y}` or `{x, y, z}` matching `t.input`) it is applied to that value directly. The table may be omitted (`t:eval()`).
---@param args torte.texture.eval.args
---@return any
function torte_texture:eval(args) end

---An analytic sphere of `radius` centred at the origin of its object space. Under a similarity transform an emitting sphere is sampled by solid angle.
---@param args torte.shape.sphere.args
---@return torte.shape
function torte.shape.sphere(args) end

---An analytic disk (an annulus when `inner_radius` > 0) in the z = 0 plane of its object space, facing +z.
---@param args torte.shape.disk.args
---@return torte.shape
function torte.shape.disk(args) end

---An open analytic cylinder around the z axis of its object space, between `z_min` and `z_max`.
---@param args torte.shape.cylinder.args
---@return torte.shape
function torte.shape.cylinder(args) end

---A box of 12 triangles: [-1, 1]^3 in object space, or the box spanning `min` and `max` (both required when either is given); `transform` applies after. `min` and `max` are read only when given.
---@param args torte.shape.cube.args
---@return torte.shape
function torte.shape.cube(args) end

---A planar convex polygon, triangulated as a fan from its first point; its front side is the one from which the points run counter-clockwise.
---@param args torte.shape.polygon.args
---@return torte.shape
function torte.shape.polygon(args) end

---A triangle mesh from arrays, from a `torte.mesh` (shared, not copied), or from a PLY or OBJ file (loaded now). An OBJ file with `usemtl` statements, given without `material`, returns an array of shapes (one per MTL material, each with the mapped material and, unless `emission` is given, the material's `Ke` as emission), which `scene:add` takes like a shape. Which keys are read depends on the form: `mesh`/`file` forms do not read `positions`, `indices`, `normals` or `uvs`.
---@param args torte.shape.mesh.args
---@return any
function torte.shape.mesh(args) end

---Reads a PLY (ASCII or binary) or OBJ file (by its extension, case-insensitive), relative to the script's directory. For an OBJ it also returns its MTL materials: an array of `{name, material, emission, mesh}` (the mapped `torte.material`, the `Ke` colour as `{r, g, b}`, and that material's triangles as a `torte.mesh`), each also under its name. Missing MTL files, unknown statements and unreadable texture maps are warnings on stderr.
---@param path any
---@return torte.mesh
function torte.mesh.load(path) end

---A new mesh: `levels` rounds of 1-to-4 midpoint subdivision (triangles x 4 per level, shared edges keep the mesh closed; normals and uvs are interpolated). `displacement` moves each new vertex along the area-weighted vertex normal by displacement x edge length x a deterministic random number in [-1, 1] that depends on `seed`; with a displacement, meshes that have normals get them recomputed. The result is limited to 2^31 triangles and the memory budget (checked before the first level). The same function is the method `mesh:subdivide{...}`.
---@param mesh any
---@param args torte.mesh.subdivide.args
---@return torte.mesh
function torte.mesh.subdivide(mesh, args) end

---`torte.mesh.subdivide(mesh, {...})` as a method; its keys and errors are those of `torte.mesh.subdivide`.
---@param args any
---@return torte.mesh
function torte_mesh:subdivide(args) end

---A copy of the mesh with angle-weighted vertex normals (scans often come without any).
---@return torte.mesh
function torte_mesh:smooth_normals() end

---The lowest and highest corners of the mesh's bounding box (object space). A mesh without vertices is an error.
---@return any
function torte_mesh:bounds() end

---The transform that scales the mesh uniformly so that its `height` (y extent), `width` (the larger of its x and z extents) or `size` (its largest extent) is the given value, and moves the centre of its bounds (with `floor = true`, their bottom centre) to `center`. Give at most one of `height`, `width`, `size`; with none the height is fitted to 1. Only the one given is read.
---@param args torte.mesh.fit.args
---@param floor any
---@return torte.transform
function torte_mesh:fit(args, floor) end

---Writes the mesh as binary little-endian PLY (positions, and normals and uvs when present), which `torte.mesh.load` reads back; `path` must end in `.ply` and is relative to the working directory. Returns nothing.
---@param path any
function torte_mesh:save(path) end

---Reads a glTF 2.0 file (`.gltf` with embedded or external buffers, or `.glb`) of the default scene: `group` holds its non-emitting meshes (node transforms applied) and its `KHR_lights_punctual` lights, to place with `torte.instance{group = g.group}`; `emitters` are its emissive meshes as shapes (area lights cannot be instanced, so they go into the scene itself); `cameras` and `lights` are in file order; `materials` are keyed by name (`material<i>` for unnamed ones). Metallic materials become conductors, others a coated diffuse; `docs/formats.md` says what is approximated. Image textures are read only from files beside the model.
---@param path any
---@return any
function torte.gltf.load(path) end

---An isotropic point light (a delta light) of `intensity` in W/sr.
---@param args torte.light.point.args
---@return torte.light
function torte.light.point(args) end

---A spot light: full `intensity` within `falloff` degrees of its axis, a smooth step down to zero at `angle` (the cone's half angle). The axis points at `look_at` or along `direction`, not both.
---@param args torte.light.spot.args
---@return torte.light
function torte.light.spot(args) end

---A light from infinitely far away travelling along `direction` (a delta light), giving the irradiance `irradiance` on a surface facing it. `radiance` is another name for the same value; give one of them.
---@param args torte.light.directional.args
---@return torte.light
function torte.light.directional(args) end

---Another name for `torte.light.directional`: the same function and keys (errors say `torte.light.directional`).
---@param args any
---@return torte.light
function torte.light.distant(args) end

---Uniform radiance from every direction (a constant environment).
---@param args torte.light.infinite.args
---@return torte.light
function torte.light.infinite(args) end

---An equirectangular environment map read with OpenImageIO (`.exr`, `.hdr`, ...): the top row is straight up (+y), u = 0 looks along +x and u = 0.25 along +z, before `transform`. Sampled by a 2D distribution over the texels.
---@param args torte.light.environment.args
---@return torte.light
function torte.light.environment(args) end

---The Preetham et al. 1999 daylight model plus a sun disk; black below the horizon (put a ground in the scene). Place the sun by `sun_direction` or by `sun_elevation`/`sun_azimuth` (azimuth 0 looks along +z, 90 along +x), not both. Radiance is the model's luminance in kcd/m^2 times `scale`; the default makes a white ground in the midday sun about 0.9.
---@param args torte.light.sky.args
---@return torte.light
function torte.light.sky(args) end

---A pinhole or thin-lens perspective camera whose field of view `fov` spans the image axis named by `fov_axis`.
---@param args torte.camera.perspective.args
---@return torte.camera
function torte.camera.perspective(args) end

---A parallel projection whose view spans `extent` scene units along the image axis named by `fov_axis`. Orthographic cameras work with every integrator except `bdpt`, `vcm`, `ppm` and `mlt`.
---@param args torte.camera.orthographic.args
---@return torte.camera
function torte.camera.orthographic(args) end

---A translation by (x, y, z): three finite numbers or one `{x, y, z}` table.
---@param x any
---@param y any
---@param z any
---@return torte.transform
function torte.translate(x, y, z) end

---A scale about the origin by (x, y, z); one number `s` scales uniformly.
---@param x any
---@param y any
---@param z any
---@return torte.transform
function torte.scale(x, y, z) end

---A rotation by `degrees` about `axis` through the origin, right-handed (counter-clockwise looking down the axis towards the origin).
---@param degrees any
---@param args any
---@return torte.transform
function torte.rotate(degrees, args) end

---A transform from 16 numbers in row-major order (column vectors: the translation is m14, m24, m34). The last row must be `0, 0, 0, 1` (affine transforms only).
---@param args any
---@return torte.transform
function torte.matrix(args) end

---The identity transform.
---@return torte.transform
function torte.identity() end

---The inverse transform.
---@return torte.transform
function torte_transform:inverse() end

---The point `p` transformed (translation included), as a new table.
---@param args any
---@return any
function torte_transform:point(args) end

---A new, empty grid. An empty keyword table is accepted (`torte.voxel.grid{}`); it takes no keys, and any key is an error.
---@return torte.voxel.grid
function torte.voxel.grid() end

---Sets one voxel; `id` is an integer in [-32768, 32767] (0 clears it).
---@param x any
---@param y any
---@param z any
---@param id any
function torte_voxel_grid:set(x, y, z, id) end

---The id of one voxel (0 where nothing is set).
---@param x any
---@param y any
---@param z any
---@return integer
function torte_voxel_grid:get(x, y, z) end

---Sets the 4096 voxels of chunk (cx, cy, cz), that is [16 cx, 16 cx + 16) x [16 cy, ...) x [16 cz, ...), from `ids` in the order index = (y * 16 + z) * 16 + x (0-based, Minecraft's section order): a table of 4096 integers, or (faster) a string of 8192 bytes holding little-endian int16 values.
---@param cx any
---@param cy any
---@param cz any
---@param ids any
function torte_voxel_grid:set_chunk(cx, cy, cz, ids) end

---The number of non-empty voxels.
---@return integer
function torte_voxel_grid:count() end

---The number of chunks holding voxels.
---@return integer
function torte_voxel_grid:chunks() end

---The chunk-aligned box [lo, hi) of the chunks held, in voxel coordinates.
---@return any
function torte_voxel_grid:bounds() end

---Defines what an id looks like. For an id > 0, a cube: `material` on every face, `faces` overriding single faces, and an `emission` that makes every exposed face of the id (one whose neighbour is not a solid cube) a one-sided area light; all emitting faces of a grid form one light sampled by power. For an id < 0, a cell shape: `shape` is a group of meshes and analytic shapes (no instances) inside the unit cell; meshes in it with `emission` emit on both sides, and `emission` on the definition itself is refused. Redefining an id replaces it.
---@param args grid.define.args
function torte_voxel_grid:define(args) end

---Builds the grid's kd-tree now (`grid:shape` builds it too, when the grid changed since the last build) and returns its statistics: `voxels`, `cells` (voxels of the padded power-of-two box), `nodes`, `bytes`, `bytes_per_voxel`, `seconds`.
---@return any
function torte_voxel_grid:build() end

---A shape of the grid, built now if needed, for `scene:add`. It holds the definitions made so far; later `set` or `define` calls need a new shape. Grids are transformable and may be instanced in groups (unless they emit).
---@param args grid.shape.args
---@return torte.shape
function torte_voxel_grid:shape(args) end

---Writes the grid's chunks as a raw dump (the voxel benchmark's `TORTE_BENCH_VOXEL_WORLD` format), relative to the working directory. Returns nothing.
---@param path any
function torte_voxel_grid:save(path) end

---`grid:shape{transform, material}` as a constructor.
---@param args torte.shape.voxels.args
---@return torte.shape
function torte.shape.voxels(args) end

---The whole file as a string: a regular file (no directory, device or FIFO) of at most a quarter of `--max-memory`. `path` is relative to the working directory (use `torte.script_dir` for files beside the script). Errors name the file.
---@param path any
---@return string
function torte.data.read_file(path) end

---The names in a directory, sorted (without `.` and `..`); `nil` and a message when it cannot be read.
---@param path any
---@return any
function torte.data.list_dir(path) end

---Decompresses one zlib stream (RFC 1950); truncated, corrupt or trailing input is an error saying which. `limit` is the most bytes the output may have (a non-negative integer).
---@param s any
---@param limit any
---@return string
function torte.data.inflate(s, limit) end

---Decompresses one gzip stream (RFC 1952), as `inflate`.
---@param s any
---@param limit any
---@return string
function torte.data.gunzip(s, limit) end

---Decodes one named tag of big-endian NBT starting at byte `offset`: byte, short, int and long become integers, float and double numbers, string strings, byte arrays strings of raw bytes, lists arrays, compounds tables, int arrays integer arrays, and long arrays `torte.data.longs` userdata. Returns the value, the tag's name and the offset after it. Errors name the tag path and byte (`truncated input: an int needs 4 bytes, 2 left in 'Level.Sections[3].Y' at byte 812 of 814`).
---@param s any
---@param offset any
---@return any
function torte.data.nbt(s, offset) end

---Reads `count` unsigned `bits`-wide fields (1..32; count at most 2^24) from a `torte.data.longs` or a string (little-endian bytes), least significant bits first. Fields span unit boundaries unless `padded` is true, when each long (or byte) holds floor(64 / bits) (or floor(8 / bits)) fields and the rest is padding. Returns a string of `count` little-endian int16 values, the fields or `map[field + 1]` when a `map` array is given (missing entries give 0; without a map a field above 32767 is an error), and a table counting each field value (`counts[v + 1]`).
---@param src any
---@param bits any
---@param count any
---@param padded any
---@param map any
---@return any
function torte.data.unpack_bits(src, bits, count, padded, map) end

---A copy of `s`, a string of little-endian int16 values, with every value v that is a key of `map` replaced by `map[v]` (keys and values integers in [-32768, 32767]). With `select`, a string of one byte per value, value i goes through `maps[select:byte(i) + 1]` (a missing map leaves it).
---@param s any
---@param map any
---@return string
function torte.data.map_int16(s, map) end

---Decompresses one raw LZ4 block (no frame) of `s:sub(i, j)`, which must decompress to exactly `size` bytes (an integer in [0, 2^31)); corrupt, truncated or wrong-size input is an error saying which, and a `size` over 255 times the block's bytes is refused before anything is allocated.
---@param s any
---@param size any
---@param i any
---@param j any
---@return string
function torte.data.lz4_block(s, size, i, j) end

---One raw LZ4 block (`LZ4_compress_default`) of `s:sub(i, j)`, for tests and writers.
---@param s any
---@param i any
---@param j any
---@return string
function torte.data.lz4_compress(s, i, j) end

---XXH32 of `s:sub(i, j)` with `seed` (an integer, taken modulo 2^32), an integer in [0, 2^32).
---@param s any
---@param seed any
---@param i any
---@param j any
---@return integer
function torte.data.xxhash32(s, seed, i, j) end

---The long array as a Lua array of integers.
---@return any
function torte_data_longs:table() end

---`torte.data.unpack_bits(longs, bits, count, padded, map)` as a method.
---@param bits any
---@param count any
---@param padded any
---@param map any
---@return any
function torte_data_longs:unpack_bits(bits, count, padded, map) end

---The targets this CPU runs, best first, as `torte.simd.use` and `--simd` name them (from `avx512`, `avx2`, `sse4`, `ssse3`, `scalar`).
---@return any
function torte.simd.targets() end

---Makes later renders and kernels run on target `name` (`"auto"`: the best this CPU runs) and returns the target now chosen. A target the CPU lacks is an error naming those it runs.
---@param name any
---@return string
function torte.simd.use(name) end

---The target kernels dispatch to now (e.g. `"avx2"`).
---@return string
function torte.simd.current() end

---Times one traversal kernel on one kind of ray through the scene, on a chosen SIMD target, and validates every result against the scalar single-ray reference. Rays: `camera` (one per pixel centre, in 4x4 blocks), `diffuse` (a cosine-distributed ray from each camera hit) or `shadow` (from each camera hit towards a sampled light; needs lights). Returns `{mrays, mrays_min, mrays_max, seconds (median), rays, hits, reference_hits, mismatches, valid, kernel, rays_kind, simd, reference_simd, threads, scene_reused}`; `valid` is false when more than 1 ray in 10^4 disagrees with the reference, the single-ray kernel on the lowest target compiled in (`reference_simd`: "scalar" in every build but the one-target sanitizer builds). Camera and diffuse rays also give `nodes_per_ray` and `prims_per_ray`: the mean acceleration nodes visited and primitives tested per ray on the reference target (the counts of the `traversal_cost` AOV), a measure of the tree's quality beside its speed. The script's SIMD target is restored afterwards.
---@param args torte.bench.args
---@return table
function torte.bench(args) end

---The script's command-line arguments (`torte.args`) merged over `defaults`, a table of the scene's arguments and their default values. An argument the table does not declare, or one whose type differs from its default's (a number for a number, `true`/`false` for a boolean; anything is taken as text for a string), is an error at the caller's line listing what the scene accepts. Under `--list-args` it prints the declared arguments (name, type, default) and ends the script, which exits with 0. Unlike keyword tables of the bindings, the argument names are the scene's own.
---@param defaults any
---@return table
function torte.options(defaults) end

---The `key=value` arguments of the command line (numbers and booleans converted); also passed to the script as `...`. Not strict: an absent key is `nil`.
---`torte.args: table`
torte.args = nil

---The script's directory as an absolute path, for `dofile`, `io.open` and `torte.data.read_file` of files beside it (`scenes/cornell-box.lua` loads its shared geometry with `dofile(torte.script_dir .. "/lib/cornell-box.lua")(torte)`, which returns the scene and camera).
---`torte.script_dir: string`
torte.script_dir = nil

---Whether `--quick` was given (renders then run at a quarter of their size and at most 4 spp), so a script can cut its own costs too.
---`torte.quick: boolean`
torte.quick = nil

---Whether `--quiet` was given; Lua libraries (the Minecraft loader) print no progress then either.
---`torte.quiet: boolean`
torte.quiet = nil

---This process's rank in a distributed render (`mpirun -n R torte ...`: every rank runs the script; only rank 0 writes images), 0 otherwise.
---`torte.rank: integer`
torte.rank = nil

---The number of ranks rendering (1 without MPI).
---`torte.ranks: integer`
torte.ranks = nil

---torte's version, e.g. `"0.1.0"`.
---`torte.version: string`
torte.version = nil

---Whether `--sandbox` restricts this run (no programs, C modules, environment or debug library; reads and writes only in allowed directories: `docs/security.md`).
---@return boolean
function torte.sandboxed() end

---Wall-clock seconds from an arbitrary start (a steady clock: differences time a step; `os.clock()` is CPU time, which counts every thread of a parallel step).
---@return number
function torte.clock() end

---@class torte.scene.args
---@field bvh_layout? string the triangles' layout, from the fastest to the smallest; `"auto"`: default when the process's resident memory plus 44 bytes per triangle of the scene fits `memory_budget`, else packed when 26 bytes per triangle fit, else compact (default "auto")
---@field memory_budget? any what `"auto"` compares with (default the process's memory limit (`--max-memory`))

---@class torte.instance.args
---@field group torte.scene what is placed
---@field transform? torte.transform group space to the space of the scene it is added to (default identity)

---@class torte.render.args
---@field scene torte.scene what to render
---@field camera torte.camera the viewpoint
---@field width? integer image width in pixels (default 512)
---@field height? integer image height in pixels (default 512)
---@field spp? integer samples per pixel (iterations for `ppm`) (default 16)
---@field max_depth? integer scattering events on a path (default 64)
---@field rr_depth? integer Russian roulette from this many scattering events on (default 3)
---@field tile_size? integer tile edge in pixels (default 16)
---@field integrator? string light transport algorithm (`docs/integrators.md`) (default "path")
---@field sample_all_lights? boolean next-event estimation towards every light instead of one (default true` for `direct` and `igi`, else `false)
---@field light_sampler? string how the one light of next-event estimation is picked (default "bvh")
---@field vpl_sets? integer `igi`: independent VPL sets per sample index (default 4)
---@field light_paths? integer `igi`: light paths per VPL set (default 64)
---@field g_limit? number `igi`: clamp of the geometry term, relative to 1/R^2 (R the scene's bounding radius) (default 20)
---@field vpl_roulette? number `igi`: throughput fraction below which light paths continue by Russian roulette (default 0.25)
---@field radius? number `vcm`, `ppm`: merge radius of the first iteration, relative to the scene's bounding radius (default 0.01)
---@field alpha? number `vcm`, `ppm`: radius schedule, iteration i merges within radius * i^((alpha - 1) / 2) (default 0.75)
---@field large_step? number `mlt`: probability that a mutation draws a fresh path (default 0.3)
---@field chains? integer `mlt`: Markov chains (0: width * height * spp / 64, at most 4096) (default 0)
---@field noise_threshold? number adaptive sampling: a pixel stops when its relative error is below this (0: off) (default 0)
---@field adaptive_min_spp? integer adaptive sampling: samples every pixel takes first (default 16)
---@field time_limit? number seconds; the render stops at the first pass boundary after it (0: none) (default 0)
---@field seed? integer random seed; the same seed gives the same image (default 0)
---@field filter? torte.filter pixel reconstruction filter (`torte.filter.*`) (default torte.filter.box{})
---@field stats? boolean collect the per-stage profile into `image.stages` (default false)
---@field aovs? string[] extra image layers (written as layers of an EXR) (default none)
---@field denoise? boolean denoise the image, guided by albedo, normal, depth, emission and glossiness layers it adds and by each pixel's variance (layer `"variance"`); the input stays as layer `"noisy"` (default false)
---@field aov_samples? integer camera samples per pixel of the AOV pass (five times as many where they disagree: outlines, creases) (default min(spp, 16))
---@field bvh_layout? string the triangles' layout for this render (a change rebuilds the scene) (default the scene's (`torte.scene`))
---@field memory_budget? any what `bvh_layout = "auto"` compares with, for this render (default the scene's (`torte.scene`))

---@class image.write.args
---@field exposure? number display files: pixels are scaled by 2^exposure (default 0)
---@field tonemap? string display files: the view transform (default "standard")

---@class torte.denoise.args
---@field strength? number scales the luminance tolerance (in standard deviations of the noise estimate) (default 1)
---@field iterations? integer filter passes (steps 1, 2, 4, ...) (default 5)

---@class torte.filter.box.args
---@field radius? number half-width in pixels (default 0.5)

---@class torte.filter.triangle.args
---@field radius? number half-width in pixels (default 1)

---@class torte.filter.gaussian.args
---@field radius? number half-width in pixels (default 1.5)
---@field sigma? number standard deviation in pixels (default 0.5)

---@class torte.filter.mitchell.args
---@field radius? number half-width in pixels (default 2)
---@field b? number the B parameter (default 1/3)
---@field c? number the C parameter (default 1/3)

---@class torte.material.matte.args
---@field color? number|number[]|torte.texture diffuse albedo (default 0.5)
---@field sigma? number|torte.texture Oren-Nayar roughness (standard deviation of the facet angle); 0 is Lambert (default 0)

---@class torte.material.plastic.args
---@field color? number|number[]|torte.texture albedo of the diffuse base (default 0.5)
---@field eta? number|torte.texture index of refraction of the coating (default 1.5)
---@field remap_roughness? boolean `true`: roughness values are squared into the alpha; `false`: they are the alpha (default true)
---@field roughness? number|torte.texture isotropic roughness of the coating (default 0.1)
---@field roughness_u? number|torte.texture anisotropic roughness along dp/du (default 0.1)
---@field roughness_v? number|torte.texture anisotropic roughness along dp/dv (default 0.1)
---@field distribution? string microfacet distribution (default "ggx")

---@class torte.material.metal.args
---@field metal? string measured metal (default aluminium)
---@field eta? number|number[]|torte.texture real part of the index of refraction, per channel (default the preset's (aluminium))
---@field k? number|number[]|torte.texture absorption coefficient, per channel (default the preset's (aluminium))
---@field remap_roughness? boolean as for `torte.material.plastic` (default true)
---@field roughness? number|torte.texture isotropic roughness (default 0.1)
---@field roughness_u? number|torte.texture anisotropic roughness along dp/du (default 0.1)
---@field roughness_v? number|torte.texture anisotropic roughness along dp/dv (default 0.1)
---@field distribution? string microfacet distribution (default "ggx")

---@class torte.material.mirror.args
---@field color? number|number[]|torte.texture reflectance (default 1)

---@class torte.material.glass.args
---@field eta? number|torte.texture index of refraction, inside over outside (default 1.5)
---@field color? number|number[]|torte.texture transmission tint (default 1)
---@field reflect_color? number|number[]|torte.texture reflection tint (default 1)
---@field thin? boolean a thin slab instead of a solid boundary (default false)

---@class torte.material.rough_glass.args
---@field eta? number|torte.texture index of refraction, inside over outside (default 1.5)
---@field color? number|number[]|torte.texture transmission tint (default 1)
---@field reflect_color? number|number[]|torte.texture reflection tint (default 1)
---@field remap_roughness? boolean as for `torte.material.plastic` (default true)
---@field roughness? number|torte.texture isotropic roughness (default 0.1)
---@field roughness_u? number|torte.texture anisotropic roughness along dp/du (default 0.1)
---@field roughness_v? number|torte.texture anisotropic roughness along dp/dv (default 0.1)
---@field distribution? string microfacet distribution (default "ggx")

---@class torte.material.mix.args
---@field a torte.material the material at amount 0
---@field b torte.material the material at amount 1
---@field amount? number|torte.texture probability of `b` (default 0.5)

---@class torte.material.bump.args
---@field material torte.material the wrapped material
---@field height? number|torte.texture height field (default 0)
---@field normal_map? number|number[]|torte.texture tangent-space normals (default none)
---@field scale? number height multiplier (scene units), or the normal map's x and y factor (default 1)

---@class torte.material.mask.args
---@field material torte.material the material where the surface is present
---@field alpha? number|torte.texture coverage (default 1)
---@field cutoff? number alpha below this is cut out (not with `stochastic`) (default 0.5)
---@field stochastic? boolean present with probability alpha instead of the cutoff (default false)

---@class torte.texture.constant.args
---@field value any the value

---@class torte.texture.uv.args
---@field scale? any uv multiplier (default 1)
---@field offset? any added after scaling (default 0)

---@class torte.texture.spherical.args
---@field transform? torte.transform mapping space to world (default identity)

---@class torte.texture.cylindrical.args
---@field transform? torte.transform mapping space to world (default identity)

---@class torte.texture.planar.args
---@field s? number[] u axis (default {1, 0, 0})
---@field t? number[] v axis (default {0, 1, 0})
---@field offset? any added to (u, v) (default 0)
---@field transform? torte.transform mapping space to world (default identity)

---@class torte.texture.xyz.args
---@field transform? torte.transform mapping space to world; `torte.scale(2)` makes a pattern twice as large (default identity)

---@class torte.texture.checker.args
---@field a? torte.texture value of the even cells (default 1)
---@field b? torte.texture value of the odd cells (default 0)
---@field scale? number cells per unit (default 1)

---@class torte.texture.checker3d.args
---@field a? torte.texture value of the even cells (default 1)
---@field b? torte.texture value of the odd cells (default 0)
---@field scale? number cells per unit (default 1)

---@class torte.texture.value_noise.args
---@field dims? integer input dimension (vec2 or vec3) (default 3)
---@field seed? integer pattern seed (default 0)

---@class torte.texture.perlin.args
---@field dims? integer input dimension (vec2 or vec3) (default 3)
---@field seed? integer pattern seed (default 0)

---@class torte.texture.fbm.args
---@field dims? integer input dimension (default 3)
---@field seed? integer pattern seed (default 0)
---@field basis? string the noise summed (default "perlin")
---@field octaves? integer layers (default 6)
---@field lacunarity? number frequency factor between layers (default 2)
---@field gain? number amplitude factor between layers (default 0.5)

---@class torte.texture.turbulence.args
---@field dims? integer input dimension (default 3)
---@field seed? integer pattern seed (default 0)
---@field basis? string the noise summed (default "perlin")
---@field octaves? integer layers (default 6)
---@field lacunarity? number frequency factor between layers (default 2)
---@field gain? number amplitude factor between layers (default 0.5)

---@class torte.texture.image.args
---@field file string path, relative to the script's directory
---@field wrap? string lookups outside [0, 1] (default "periodic")
---@field filter? string texture filtering (default "trilinear")
---@field color_space? string how texel values are decoded (default "auto")

---@class torte.texture.spline.args
---@field colors any the ramp's colours
---@field positions? number[] where each colour sits (default evenly spaced on [0, 1])
---@field interpolation? string curve between colours (default "catmull-rom")

---@class torte.texture.add.args
---@field a torte.texture first operand
---@field b torte.texture second operand

---@class torte.texture.multiply.args
---@field a torte.texture first operand
---@field b torte.texture second operand

---@class torte.texture.scale.args
---@field texture torte.texture what is scaled
---@field factor number the factor

---@class torte.texture.lerp.args
---@field t torte.texture blend weight
---@field a torte.texture value at t = 0
---@field b torte.texture value at t = 1

---@class torte.texture.mix.args
---@field t torte.texture blend weight
---@field a torte.texture value at t = 0
---@field b torte.texture value at t = 1

---@class torte.texture.compose.args
---@field outer torte.texture applied second
---@field inner torte.texture applied first

---@class torte.texture.eval.args
---@field uv? any surface uv (default {0, 0})
---@field p? number[] world position (default {0, 0, 0})
---@field n? number[] surface normal (default {0, 0, 1})
---@field dpdu? number[] position derivative along u (default {0, 0, 0})
---@field dpdv? number[] position derivative along v (default {0, 0, 0})
---@field footprint? number filter width (image textures) (default 0)
---@field input? any the texture's input value (default none)

---@class torte.shape.sphere.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5)
---@field emission? number|number[]|torte.texture emitted radiance (an area light when not black) (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field radius? number radius (default 1)

---@class torte.shape.disk.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5)
---@field emission? number|number[]|torte.texture emitted radiance (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field radius? number outer radius (default 1)
---@field inner_radius? number inner radius (default 0)

---@class torte.shape.cylinder.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5)
---@field emission? number|number[]|torte.texture emitted radiance (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field radius? number radius (default 1)
---@field z_min? number lower end (default -1)
---@field z_max? number upper end (default 1)

---@class torte.shape.cube.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5)
---@field emission? number|number[]|torte.texture emitted radiance (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field min? number[] lowest corner (default {-1, -1, -1})
---@field max? number[] highest corner (default {1, 1, 1})

---@class torte.shape.polygon.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5)
---@field emission? number|number[]|torte.texture emitted radiance (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field points any the corners, in order

---@class torte.shape.mesh.args
---@field transform? torte.transform object to world (default identity)
---@field material? torte.material surface material (default matte 0.5 (OBJ: its MTL materials))
---@field emission? number|number[]|torte.texture emitted radiance (default 0)
---@field two_sided? boolean emit on both sides (default false)
---@field mesh? torte.mesh a loaded or generated `torte.mesh` (default none)
---@field file? string path, relative to the script's directory (default none)
---@field positions? any vertex positions (`{{x, y, z}, ...}` or flat) (default required without `mesh`/`file`)
---@field indices? any triangles (default required without `mesh`/`file`)
---@field normals? any shading normals (normalised) (default none)
---@field uvs? any texture coordinates (default none)

---@class torte.mesh.subdivide.args
---@field levels? integer subdivision rounds (default 1)
---@field displacement? number relative displacement of new vertices (0: none) (default 0)
---@field seed? integer seed of the displacement (default 0)

---@class torte.mesh.fit.args
---@field height? number target y extent (default 1)
---@field width? number target larger of the x and z extents (default none)
---@field size? number target largest extent (default none)
---@field center? number[] where the anchor point goes (default {0, 0, 0})
---@field floor? boolean anchor at the bottom centre instead of the centre (default false)

---@class torte.light.point.args
---@field position number[] where the light is
---@field intensity? number|number[] radiant intensity (default 1)

---@class torte.light.spot.args
---@field position number[] apex of the cone
---@field look_at? number[] a point on the axis (default none)
---@field direction? number[] the axis (normalised) (default {0, -1, 0})
---@field intensity? number|number[] radiant intensity on the axis (default 1)
---@field angle? number half angle of the cone (default 30)
---@field falloff? number half angle of the fully lit core (default max(0, angle - 5))

---@class torte.light.directional.args
---@field direction number[] the way the light travels
---@field irradiance? number|number[] irradiance on a facing surface (default 1)
---@field radiance? number|number[] the same value under another name (default 1)

---@class torte.light.infinite.args
---@field radiance? number|number[] the radiance (default 1)

---@class torte.light.environment.args
---@field file string path, relative to the script's directory
---@field transform? torte.transform light space to world (default identity)
---@field scale? number|number[] radiance multiplier (default 1)

---@class torte.light.sky.args
---@field sun_elevation? number sun height above the horizon (default `45` (when `sun_azimuth` is given))
---@field sun_azimuth? number sun bearing, from +z towards +x (default 0)
---@field sun_direction? number[] towards the sun (default {0.5, 0.7, 0.5})
---@field turbidity? number haze (2-3 clear, 6+ hazy) (default 3)
---@field scale? number radiance per kcd/m^2 (default 1/40)
---@field sun? boolean include the sun disk (default true)
---@field sun_radius? number angular radius of the sun disk (same irradiance) (default 0.2665)

---@class torte.camera.perspective.args
---@field transform? torte.transform camera to world (default none)
---@field eye? number[] camera position (default {0, 0, 0})
---@field look_at? number[] a point the camera looks at (default {0, 0, 1})
---@field up? number[] the image's up direction (default {0, 1, 0})
---@field aperture? number lens radius in scene units (0: pinhole) (default 0)
---@field focus_distance? number distance of the plane in focus along the view axis (default distance from `eye` to `look_at` (1 with `transform`))
---@field fov? number field of view (default 45)
---@field fov_axis? string which extent `fov` spans (default "vertical")

---@class torte.camera.orthographic.args
---@field transform? torte.transform camera to world (default none)
---@field eye? number[] camera position (default {0, 0, 0})
---@field look_at? number[] a point the camera looks at (default {0, 0, 1})
---@field up? number[] the image's up direction (default {0, 1, 0})
---@field aperture? number lens radius in scene units (0: no defocus) (default 0)
---@field focus_distance? number distance of the plane in focus (default distance from `eye` to `look_at` (1 with `transform`))
---@field extent? number width of the view along `fov_axis`, scene units (default 2)
---@field fov_axis? string which image axis `extent` spans (default "vertical")

---@class grid.define.args
---@field id integer the id defined
---@field emission? number|number[] radiance of the cube's exposed faces (default 0)
---@field material? torte.material material of every face (default the grid shape's `material`)
---@field faces? table per-face materials (default none)
---@field shape? torte.scene the cell's shapes, in [0, 1]^3 (default required for ids < 0)

---@class grid.define_faces.args
---@field side? torte.material the four faces +x, -x, +z, -z (default material)
---@field top? torte.material the +y face (default material)
---@field bottom? torte.material the -y face (default material)
---@field +x? torte.material the +x face (over `side`) (default material)
---@field -x? torte.material the -x face (over `side`) (default material)
---@field +y? torte.material the +y face (over `top`) (default material)
---@field -y? torte.material the -y face (over `bottom`) (default material)
---@field +z? torte.material the +z face (over `side`) (default material)
---@field -z? torte.material the -z face (over `side`) (default material)

---@class grid.shape.args
---@field transform? torte.transform grid space to world (default identity)
---@field material? torte.material material of ids without a definition (default matte 0.5)

---@class torte.shape.voxels.args
---@field grid any the grid
---@field transform? torte.transform grid space to world (default identity)
---@field material? torte.material material of ids without a definition (default matte 0.5)

---@class torte.bench.args
---@field scene torte.scene what is traced
---@field camera torte.camera where the camera rays start
---@field rays? string which rays are timed (default "camera")
---@field kernel? string traversal kernel (default "packet8")
---@field width? integer camera rays across (default 512)
---@field height? integer camera rays down (default 512)
---@field reps? integer timed repetitions (default 5)
---@field threads? integer threads tracing (default 1)
---@field seed? integer seed of the secondary rays (default 0)
---@field simd? string target timed (default the run's target)

return torte
