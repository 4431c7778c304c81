-- minecraft.blocks: what Minecraft blocks look like, as torte materials and unit-cell shapes, and the registry
-- that gives each block state seen in a world a 16-bit voxel id.
--
--   local blocks = require "minecraft.blocks"
--   local reg = blocks.registry()
--   local id = reg:state("minecraft:oak_slab", {type = "top"})   -- voxel id: > 0 cube, < 0 cell shape, 0 = none
--   local id2 = reg:legacy(44, 8)                                 -- pre-1.13 numeric id + data nibble
--   reg:define(grid)      -- grid:define{...} for every id handed out (materials built on first use)
--   reg.unknown           -- {["minecraft:foo"] = number of blocks} drawn with the fallback (magenta) look
--   reg:tinted(id, "swamp")   -- the biome variant of a tinted block (grass, leaves, vines, water): a new id
--   reg:tint(id)              -- its tint class (nil: untinted); reg.tint_kind[id] = "grass" | "foliage" | "water"
--   reg:connected(id, {north = true, east = false, ...})   -- a fence, wall or pane with those connections
--   reg.family[id], reg:solid(id)   -- what fences, walls and panes join (minecraft.world.connect_section)
--   reg:ids_of("minecraft:water")   -- every id of a block name, as a set
--
-- Looks are procedural (noise-tinted colours, no game assets). Colours below are sRGB-ish as one would pick
-- them; they are linearised when materials are made.
local torte = require "torte"
local biomes = require "minecraft.biomes"

local M = {}

M.AIR = {["minecraft:air"] = true, ["minecraft:cave_air"] = true, ["minecraft:void_air"] = true}
M.FALLBACK_COLOR = {0.95, 0.1, 0.85}

-- ---- colours --------------------------------------------------------------------------------------------------
local DYES = {
  white = {0.92, 0.92, 0.92}, orange = {0.94, 0.46, 0.08}, magenta = {0.75, 0.27, 0.71},
  light_blue = {0.23, 0.68, 0.85}, yellow = {0.97, 0.78, 0.15}, lime = {0.44, 0.73, 0.1},
  pink = {0.93, 0.55, 0.67}, gray = {0.25, 0.27, 0.29}, light_gray = {0.56, 0.56, 0.53},
  cyan = {0.08, 0.54, 0.57}, purple = {0.47, 0.16, 0.67}, blue = {0.2, 0.22, 0.6},
  brown = {0.45, 0.28, 0.16}, green = {0.33, 0.43, 0.11}, red = {0.63, 0.14, 0.13}, black = {0.08, 0.08, 0.1},
}
M.DYE_ORDER = {"white", "orange", "magenta", "light_blue", "yellow", "lime", "pink", "gray", "light_gray",
               "cyan", "purple", "blue", "brown", "green", "red", "black"}
local PLANKS = {
  oak = {0.66, 0.53, 0.33}, spruce = {0.45, 0.33, 0.2}, birch = {0.78, 0.71, 0.5}, jungle = {0.63, 0.45, 0.32},
  acacia = {0.66, 0.35, 0.2}, dark_oak = {0.26, 0.17, 0.08}, mangrove = {0.46, 0.21, 0.2},
  cherry = {0.89, 0.7, 0.68}, crimson = {0.4, 0.2, 0.28}, warped = {0.17, 0.41, 0.39}, bamboo = {0.77, 0.68, 0.33},
  pale_oak = {0.89, 0.85, 0.82},
}
local BARK = {
  oak = {0.4, 0.31, 0.19}, spruce = {0.23, 0.15, 0.07}, birch = {0.85, 0.84, 0.8}, jungle = {0.34, 0.27, 0.1},
  acacia = {0.4, 0.38, 0.35}, dark_oak = {0.24, 0.18, 0.1}, mangrove = {0.33, 0.26, 0.16},
  cherry = {0.21, 0.13, 0.15}, crimson = {0.36, 0.1, 0.15}, warped = {0.23, 0.23, 0.3}, pale_oak = {0.45, 0.42, 0.4},
}
local LEAVES = {
  oak = {0.22, 0.48, 0.12}, spruce = {0.22, 0.38, 0.22}, birch = {0.42, 0.58, 0.26}, jungle = {0.2, 0.56, 0.1},
  acacia = {0.32, 0.52, 0.1}, dark_oak = {0.2, 0.45, 0.1}, mangrove = {0.3, 0.5, 0.12}, cherry = {0.93, 0.67, 0.78},
  azalea = {0.36, 0.5, 0.2}, flowering_azalea = {0.45, 0.5, 0.35}, pale_oak = {0.6, 0.62, 0.58},
}
local CORALS = {tube = {0.2, 0.35, 0.85}, brain = {0.85, 0.4, 0.65}, bubble = {0.65, 0.15, 0.65},
                fire = {0.8, 0.2, 0.2}, horn = {0.85, 0.8, 0.25}}
local STONE = {0.49, 0.49, 0.49}
local DIRT = {0.53, 0.38, 0.26}
local GRASS = {0.45, 0.7, 0.3}

-- ---- definitions ----------------------------------------------------------------------------------------------
-- A definition: color (all faces) or top/side/bottom colours; `mat` picks a material kind (matte by default;
-- "glass", "water", "ice", "metal", "plastic", "leaves"); `emit` makes an emitter (radiance, linear);
-- `shape` makes a cell shape instead of a cube ("slab", "stairs", "cross", "flower", "torch", "layer", "pane",
-- "fence", "wall", "gate", "door", "carpet", "scaffold"); `invisible` = not drawn. `tint` = "grass", "foliage" or
-- "water": the colour (grass_block: its top) follows the biome (minecraft.biomes; the colours here are plains).
-- `connect` = the family a fence, wall or pane connects to (besides solid cubes): "wood_fence", "nether_fence",
-- "pane", "wall".
local D = {}
M.DEFS = D
local function def(names, t)
  for name in names:gmatch("%S+") do D[name] = t end
end

def("stone infested_stone", {color = STONE})
def("granite", {color = {0.6, 0.42, 0.35}})
def("polished_granite", {color = {0.63, 0.44, 0.37}, noise = 0.1})
def("diorite", {color = {0.74, 0.74, 0.75}})
def("polished_diorite", {color = {0.77, 0.77, 0.78}, noise = 0.1})
def("andesite", {color = {0.53, 0.53, 0.53}})
def("polished_andesite", {color = {0.52, 0.54, 0.53}, noise = 0.1})
def("deepslate cobbled_deepslate polished_deepslate deepslate_bricks deepslate_tiles",
    {color = {0.3, 0.3, 0.32}})
def("tuff", {color = {0.42, 0.43, 0.39}})
def("calcite", {color = {0.87, 0.88, 0.86}})
def("smooth_stone", {color = {0.62, 0.62, 0.62}, noise = 0.1})
def("cobblestone", {color = {0.48, 0.48, 0.48}, noise = 0.5})
def("mossy_cobblestone", {color = {0.42, 0.48, 0.38}, noise = 0.5})
def("stone_bricks chiseled_stone_bricks cracked_stone_bricks infested_stone_bricks", {color = {0.48, 0.48, 0.48}})
def("mossy_stone_bricks", {color = {0.45, 0.5, 0.4}})
def("bedrock", {color = {0.33, 0.33, 0.33}, noise = 0.6})
def("dirt coarse_dirt rooted_dirt", {color = DIRT})
def("mud", {color = {0.24, 0.22, 0.24}})
def("farmland", {top = {0.32, 0.2, 0.1}, side = DIRT, bottom = DIRT})
def("dirt_path grass_path", {top = {0.58, 0.49, 0.27}, side = DIRT, bottom = DIRT})
def("grass_block", {top = GRASS, side = {0.5, 0.47, 0.3}, bottom = DIRT, tint = "grass"})
def("podzol", {top = {0.36, 0.25, 0.1}, side = DIRT, bottom = DIRT})
def("mycelium", {top = {0.44, 0.37, 0.41}, side = DIRT, bottom = DIRT})
def("snowy_grass_block", {top = {0.95, 0.97, 0.98}, side = {0.75, 0.72, 0.68}, bottom = DIRT})
def("clay", {color = {0.63, 0.65, 0.71}})
def("sand suspicious_sand", {color = {0.86, 0.81, 0.6}})
def("red_sand", {color = {0.75, 0.4, 0.13}})
def("gravel suspicious_gravel", {color = {0.53, 0.5, 0.49}, noise = 0.6})
def("sandstone cut_sandstone chiseled_sandstone smooth_sandstone",
    {top = {0.88, 0.83, 0.62}, side = {0.85, 0.8, 0.6}, bottom = {0.84, 0.78, 0.57}})
def("red_sandstone cut_red_sandstone chiseled_red_sandstone smooth_red_sandstone", {color = {0.73, 0.39, 0.12}})
def("coal_ore deepslate_coal_ore", {color = STONE, spots = {0.1, 0.1, 0.1}})
def("iron_ore deepslate_iron_ore", {color = STONE, spots = {0.85, 0.7, 0.58}})
def("copper_ore deepslate_copper_ore", {color = STONE, spots = {0.8, 0.45, 0.3}})
def("gold_ore deepslate_gold_ore nether_gold_ore", {color = STONE, spots = {0.98, 0.86, 0.25}})
def("redstone_ore deepslate_redstone_ore", {color = STONE, spots = {0.85, 0.05, 0.05}})
def("lapis_ore deepslate_lapis_ore", {color = STONE, spots = {0.15, 0.3, 0.75}})
def("diamond_ore deepslate_diamond_ore", {color = STONE, spots = {0.4, 0.9, 0.85}})
def("emerald_ore deepslate_emerald_ore", {color = STONE, spots = {0.2, 0.85, 0.4}})
def("nether_quartz_ore", {color = {0.45, 0.18, 0.17}, spots = {0.9, 0.88, 0.85}})
def("coal_block", {color = {0.09, 0.09, 0.09}})
def("iron_block", {color = {0.85, 0.85, 0.85}, mat = "metal", roughness = 0.4})
def("gold_block", {color = {0.98, 0.85, 0.3}, mat = "metal", metal = "gold", roughness = 0.3})
def("diamond_block", {color = {0.4, 0.9, 0.85}, mat = "plastic"})
def("emerald_block", {color = {0.2, 0.8, 0.35}, mat = "plastic"})
def("lapis_block", {color = {0.12, 0.27, 0.6}})
def("redstone_block", {color = {0.7, 0.08, 0.05}})
def("copper_block cut_copper", {color = {0.75, 0.42, 0.3}, mat = "metal", metal = "copper", roughness = 0.4})
def("raw_iron_block", {color = {0.65, 0.53, 0.42}})
def("obsidian crying_obsidian", {color = {0.08, 0.06, 0.13}, mat = "plastic"})
def("bricks", {color = {0.59, 0.33, 0.26}})
def("bookshelf", {top = PLANKS.oak, bottom = PLANKS.oak, side = {0.45, 0.3, 0.2}})
def("tnt", {top = {0.85, 0.3, 0.2}, side = {0.82, 0.2, 0.15}, bottom = {0.85, 0.3, 0.2}})
def("crafting_table", {top = {0.55, 0.38, 0.22}, side = {0.48, 0.34, 0.2}, bottom = PLANKS.oak})
def("furnace dispenser dropper observer", {color = {0.45, 0.45, 0.45}})
def("note_block jukebox", {color = {0.45, 0.3, 0.22}})
def("glass tinted_glass", {color = {0.9, 0.95, 0.95}, mat = "glass"})
def("glass_pane", {color = {0.9, 0.95, 0.95}, mat = "glass", shape = "pane", connect = "pane"})
def("iron_bars", {color = {0.6, 0.6, 0.62}, mat = "metal", roughness = 0.5, shape = "pane", connect = "pane"})
def("ice frosted_ice", {color = {0.6, 0.75, 0.98}, mat = "ice"})
def("packed_ice blue_ice", {color = {0.55, 0.7, 0.95}, mat = "plastic"})
def("snow_block powder_snow", {color = {0.96, 0.98, 0.98}, noise = 0.1})
def("snow", {color = {0.96, 0.98, 0.98}, noise = 0.1, shape = "layer"})
-- Water: a cell shape holding only the surface (a dielectric quad 14/16 up the cell). world.water_surfaces()
-- empties water cells under other water, so a ray crosses one interface instead of one per block.
def("water bubble_column", {color = {0.75, 0.85, 0.95}, mat = "water", shape = "water", tint = "water"})
def("lava", {color = {0.9, 0.35, 0.05}, emit = {4.0, 1.2, 0.15}})
def("magma_block", {color = {0.55, 0.2, 0.08}, emit = {0.6, 0.15, 0.02}})
def("glowstone", {color = {0.9, 0.75, 0.45}, emit = {6, 4.5, 2.5}})
def("sea_lantern", {color = {0.8, 0.9, 0.9}, emit = {4, 5, 5}})
def("shroomlight", {color = {0.95, 0.6, 0.3}, emit = {5, 3, 1.2}})
def("jack_o_lantern", {color = {0.85, 0.5, 0.1}, emit = {3, 1.8, 0.5}})
def("redstone_lamp", {color = {0.45, 0.3, 0.2}})
def("torch wall_torch", {color = {0.55, 0.42, 0.25}, shape = "torch", emit = {8, 5.5, 2.5}})
def("redstone_torch redstone_wall_torch", {color = {0.6, 0.15, 0.1}, shape = "torch", emit = {2, 0.2, 0.1}})
def("soul_torch soul_wall_torch", {color = {0.4, 0.5, 0.55}, shape = "torch", emit = {1.5, 4, 4.5}})
def("lantern", {color = {0.3, 0.3, 0.32}, shape = "torch", emit = {8, 5.5, 2.5}})
def("end_rod", {color = {0.95, 0.92, 0.88}, shape = "torch", emit = {5, 5, 5}})
def("fire", {color = {0.95, 0.55, 0.1}, shape = "cross", emit = {6, 3, 0.6}})
def("pumpkin carved_pumpkin", {top = {0.78, 0.5, 0.12}, side = {0.85, 0.5, 0.1}, bottom = {0.78, 0.5, 0.12}})
def("melon", {top = {0.55, 0.6, 0.15}, side = {0.45, 0.6, 0.15}, bottom = {0.55, 0.6, 0.15}})
def("hay_block", {top = {0.75, 0.65, 0.15}, side = {0.8, 0.66, 0.1}, bottom = {0.75, 0.65, 0.15}})
def("cactus", {top = {0.35, 0.55, 0.2}, side = {0.25, 0.5, 0.15}, bottom = {0.35, 0.55, 0.2}})
def("sponge wet_sponge", {color = {0.8, 0.78, 0.3}})
def("netherrack", {color = {0.43, 0.18, 0.18}})
def("soul_sand soul_soil", {color = {0.33, 0.25, 0.2}})
def("nether_bricks red_nether_bricks", {color = {0.22, 0.11, 0.13}})
def("end_stone end_stone_bricks", {color = {0.86, 0.87, 0.63}})
def("purpur_block purpur_pillar", {color = {0.66, 0.49, 0.66}})
def("quartz_block smooth_quartz chiseled_quartz_block quartz_pillar quartz_bricks", {color = {0.92, 0.9, 0.86},
                                                                                      noise = 0.05})
def("prismarine prismarine_bricks", {color = {0.39, 0.63, 0.57}})
def("dark_prismarine", {color = {0.2, 0.35, 0.3}})
def("slime_block", {color = {0.45, 0.75, 0.35}, mat = "plastic"})
def("bone_block", {top = {0.82, 0.8, 0.7}, side = {0.88, 0.86, 0.78}, bottom = {0.82, 0.8, 0.7}})
def("terracotta", {color = {0.6, 0.37, 0.27}})
def("moss_block moss_carpet", {color = {0.35, 0.47, 0.18}})
def("brown_mushroom_block", {color = {0.58, 0.44, 0.33}})
def("red_mushroom_block", {color = {0.78, 0.18, 0.16}})
def("mushroom_stem", {color = {0.8, 0.78, 0.72}})
def("chest trapped_chest barrel", {color = {0.62, 0.45, 0.2}})
def("spawner", {color = {0.15, 0.2, 0.25}, mat = "metal", roughness = 0.5})
def("enchanting_table end_portal_frame", {color = {0.25, 0.4, 0.35}})
def("bed red_bed", {color = {0.63, 0.14, 0.13}, shape = "slab_low"})
def("cake", {color = {0.9, 0.85, 0.8}, shape = "slab"})
def("dried_kelp_block", {color = {0.22, 0.25, 0.15}})
def("amethyst_block budding_amethyst", {color = {0.55, 0.4, 0.75}})
def("dripstone_block pointed_dripstone", {color = {0.53, 0.42, 0.36}})
def("blackstone polished_blackstone polished_blackstone_bricks basalt polished_basalt",
    {color = {0.17, 0.15, 0.18}})
def("beacon", {color = {0.5, 0.85, 0.85}, emit = {4, 6, 6}})
-- Plants: small primitives.
def("grass short_grass fern tall_grass large_fern", {color = {0.35, 0.6, 0.22}, shape = "cross", tint = "grass"})
def("seagrass tall_seagrass kelp kelp_plant", {color = {0.35, 0.6, 0.22}, shape = "cross"})
def("dead_bush", {color = {0.55, 0.4, 0.2}, shape = "cross"})
def("sugar_cane reeds", {color = {0.5, 0.7, 0.35}, shape = "cross", tint = "grass"})
def("wheat carrots potatoes beetroots", {color = {0.55, 0.65, 0.2}, shape = "cross"})
def("vine", {color = {0.25, 0.5, 0.15}, shape = "carpet", tint = "foliage"})
def("glow_lichen", {color = {0.25, 0.5, 0.15}, shape = "carpet"})
def("lily_pad", {color = {0.2, 0.5, 0.15}, shape = "carpet"})
def("cobweb", {color = {0.9, 0.9, 0.9}, shape = "cross"})
def("dandelion sunflower", {color = {0.95, 0.85, 0.1}, shape = "flower"})
def("poppy rose_bush red_tulip", {color = {0.85, 0.1, 0.08}, shape = "flower"})
def("blue_orchid cornflower", {color = {0.2, 0.55, 0.9}, shape = "flower"})
def("allium lilac peony", {color = {0.75, 0.45, 0.85}, shape = "flower"})
def("azure_bluet oxeye_daisy white_tulip lily_of_the_valley", {color = {0.95, 0.95, 0.9}, shape = "flower"})
def("orange_tulip", {color = {0.95, 0.5, 0.1}, shape = "flower"})
def("pink_tulip", {color = {0.95, 0.65, 0.8}, shape = "flower"})
def("brown_mushroom", {color = {0.6, 0.45, 0.33}, shape = "flower"})
def("red_mushroom", {color = {0.8, 0.15, 0.12}, shape = "flower"})
def("rail powered_rail detector_rail activator_rail redstone_wire", {color = {0.45, 0.4, 0.35}, shape = "carpet"})
def("ladder", {color = PLANKS.oak, shape = "carpet"})
def("barrier structure_void light moving_piston", {invisible = true})
-- Deep dark, caves, redstone and the odd blocks of the debug worlds.
def("chiseled_deepslate cracked_deepslate_bricks cracked_deepslate_tiles reinforced_deepslate",
    {color = {0.3, 0.3, 0.32}})
def("sculk sculk_catalyst", {color = {0.05, 0.12, 0.16}})
def("sculk_vein", {color = {0.05, 0.2, 0.25}, shape = "carpet"})
def("sculk_sensor sculk_shrieker calibrated_sculk_sensor", {color = {0.1, 0.3, 0.35}, shape = "slab"})
def("amethyst_cluster large_amethyst_bud medium_amethyst_bud small_amethyst_bud", {color = {0.7, 0.5, 0.9},
                                                                                   shape = "cross"})
def("raw_copper_block", {color = {0.6, 0.4, 0.3}})
def("raw_gold_block", {color = {0.85, 0.65, 0.2}})
def("smooth_basalt", {color = {0.28, 0.28, 0.3}})
def("bee_nest beehive", {top = {0.75, 0.6, 0.3}, side = {0.8, 0.65, 0.35}, bottom = {0.75, 0.6, 0.3}})
def("chain iron_chain", {color = {0.25, 0.27, 0.3}, shape = "torch"})
def("candle", {color = {0.9, 0.85, 0.7}, shape = "torch", emit = {2, 1.4, 0.6}})
def("azalea flowering_azalea", {color = {0.36, 0.5, 0.2}, shape = "flower"})
def("big_dripleaf small_dripleaf", {color = {0.35, 0.6, 0.2}, shape = "slab_top"})
def("big_dripleaf_stem cave_vines cave_vines_plant weeping_vines twisting_vines hanging_roots spore_blossom",
    {color = {0.3, 0.5, 0.2}, shape = "cross"})
def("glow_berries", {color = {0.9, 0.6, 0.2}, shape = "cross"})
def("lever comparator repeater daylight_detector tripwire tripwire_hook stone_button heavy_weighted_pressure_plate "
    .. "light_weighted_pressure_plate", {color = {0.55, 0.55, 0.55}, shape = "carpet"})
def("lectern cauldron anvil chipped_anvil damaged_anvil brewing_stand hopper enchanting_table piston_head "
    .. "stonecutter grindstone smithing_table", {color = {0.35, 0.35, 0.37}, shape = "slab"})
def("piston sticky_piston", {top = {0.6, 0.5, 0.35}, side = {0.45, 0.45, 0.45}, bottom = {0.45, 0.45, 0.45}})
def("command_block chain_command_block repeating_command_block structure_block jigsaw",
    {color = {0.55, 0.45, 0.35}, mat = "plastic"})
def("chorus_plant chorus_flower", {color = {0.55, 0.4, 0.55}})
def("cocoa nether_wart melon_stem pumpkin_stem attached_melon_stem attached_pumpkin_stem sweet_berry_bush "
    .. "bamboo bamboo_sapling", {color = {0.45, 0.55, 0.2}, shape = "cross"})
def("dragon_egg", {color = {0.1, 0.05, 0.12}, shape = "flower"})
def("end_portal end_gateway", {color = {0.02, 0.05, 0.05}, mat = "plastic"})
def("nether_portal", {color = {0.5, 0.15, 0.85}, mat = "glass"})
def("ender_chest", {color = {0.1, 0.15, 0.15}})
def("flower_pot", {color = {0.47, 0.25, 0.17}, shape = "flower"})
def("skeleton_skull skeleton_wall_skull wither_skeleton_skull zombie_head player_head creeper_head dragon_head",
    {color = {0.8, 0.8, 0.75}, shape = "flower"})
def("conduit", {color = {0.6, 0.55, 0.4}, shape = "flower", emit = {2, 3, 3}})
def("scaffolding", {color = {0.75, 0.65, 0.4}, shape = "scaffold"})
def("sea_pickle", {color = {0.45, 0.55, 0.2}, shape = "flower", emit = {0.5, 0.8, 0.6}})
def("turtle_egg", {color = {0.9, 0.9, 0.8}, shape = "flower"})
def("blast_furnace smoker", {color = {0.4, 0.4, 0.42}})
def("loom cartography_table fletching_table composter", {color = {0.55, 0.42, 0.28}})
def("bell", {color = {0.9, 0.75, 0.3}, shape = "flower"})
def("campfire soul_campfire", {color = {0.5, 0.3, 0.15}, shape = "carpet", emit = {4, 2, 0.5}})
def("honey_block", {color = {0.95, 0.65, 0.15}, mat = "plastic"})
def("honeycomb_block", {color = {0.9, 0.6, 0.15}})
def("target", {color = {0.9, 0.85, 0.8}, spots = {0.8, 0.2, 0.2}})
def("lodestone respawn_anchor", {color = {0.45, 0.45, 0.48}})
def("frogspawn", {color = {0.4, 0.35, 0.35}, shape = "carpet"})
def("pink_petals", {color = {0.95, 0.65, 0.8}, shape = "carpet"})
def("mangrove_roots muddy_mangrove_roots", {color = {0.3, 0.25, 0.18}})
def("nether_wart_block", {color = {0.45, 0.05, 0.05}})
def("warped_wart_block", {color = {0.1, 0.45, 0.4}})
def("soul_fire", {color = {0.3, 0.8, 0.9}, shape = "cross", emit = {1.5, 4, 4.5}})
def("soul_lantern", {color = {0.3, 0.3, 0.32}, shape = "torch", emit = {1.5, 4, 4.5}})
def("sign wall_sign", {color = PLANKS.oak, shape = "torch"})
def("packed_mud mud_bricks", {color = {0.55, 0.42, 0.32}})

-- Families by name pattern: returns a definition for names not listed above.
local function family(n)
  local wood = n:match("^(.-)_planks$")
  if wood then return {color = PLANKS[wood] or PLANKS.oak, noise = 0.2} end
  wood = n:match("^stripped_(.-)_log$") or n:match("^stripped_(.-)_wood$") or n:match("^stripped_(.-)_stem$")
         or n:match("^stripped_(.-)_hyphae$")
  if wood then return {color = PLANKS[wood] or PLANKS.oak, pillar = true} end
  wood = n:match("^(.-)_log$") or n:match("^(.-)_stem$")
  if wood and (BARK[wood] or PLANKS[wood]) then
    return {side = BARK[wood] or BARK.oak, top = PLANKS[wood] or PLANKS.oak, bottom = PLANKS[wood] or PLANKS.oak,
            pillar = true}
  end
  wood = n:match("^(.-)_wood$") or n:match("^(.-)_hyphae$")
  if wood then return {color = BARK[wood] or BARK.oak} end
  wood = n:match("^(.-)_leaves$")
  if wood then  -- spruce, birch, cherry and azalea leaves have fixed colours; the others follow the biome
    local fixed = wood == "spruce" or wood == "birch" or wood == "cherry" or wood:find("azalea")
    return {color = LEAVES[wood] or LEAVES.oak, mat = "leaves", tint = not fixed and "foliage" or nil}
  end
  wood = n:match("^(.-)_sapling$")
  if wood then return {color = LEAVES[wood] or LEAVES.oak, shape = "cross"} end
  local dye = n:match("^(.-)_wool$")
  if dye and DYES[dye] then return {color = DYES[dye], noise = 0.15} end
  dye = n:match("^(.-)_carpet$")
  if dye and DYES[dye] then return {color = DYES[dye], noise = 0.15, shape = "carpet"} end
  dye = n:match("^(.-)_concrete$")
  if dye and DYES[dye] then return {color = DYES[dye], noise = 0.03} end
  dye = n:match("^(.-)_concrete_powder$")
  if dye and DYES[dye] then return {color = DYES[dye], noise = 0.3} end
  dye = n:match("^(.-)_glazed_terracotta$") or n:match("^(.-)_terracotta$")
  if dye and DYES[dye] then
    local c = DYES[dye]
    return {color = {0.55 * c[1] + 0.25, 0.55 * c[2] + 0.17, 0.55 * c[3] + 0.13}}
  end
  dye = n:match("^(.-)_stained_glass_pane$")
  if dye and DYES[dye] then return {color = DYES[dye], mat = "glass", shape = "pane", connect = "pane"} end
  dye = n:match("^(.-)_stained_glass$")
  if dye and DYES[dye] then return {color = DYES[dye], mat = "glass"} end
  dye = n:match("^(.-)_shulker_box$")
  if dye and DYES[dye] then return {color = DYES[dye]} end
  dye = n:match("^(.-)_bed$")
  if dye and DYES[dye] then return {color = DYES[dye], shape = "slab_low"} end
  if n == "shulker_box" then return {color = {0.6, 0.45, 0.6}} end
  local coral = n:match("^dead_(.-)_coral_block$") or n:match("^(.-)_coral_block$")
  if coral then return {color = n:find("^dead_") and {0.5, 0.47, 0.45} or CORALS[coral] or {0.8, 0.4, 0.6}} end
  coral = n:match("^dead_(.-)_coral") or n:match("^(.-)_coral")
  if coral then
    return {color = n:find("^dead_") and {0.5, 0.47, 0.45} or CORALS[coral] or {0.8, 0.4, 0.6}, shape = "cross"}
  end
  dye = n:match("^(.-)_wall_banner$") or n:match("^(.-)_banner$")
  if dye and DYES[dye] then return {color = DYES[dye], shape = "torch"} end
  dye = n:match("^(.-)_candle$")
  if dye and DYES[dye] then return {color = DYES[dye], shape = "torch", emit = {2, 1.4, 0.6}} end
  if n:match("^potted_") then return {color = {0.47, 0.25, 0.17}, shape = "flower"} end
  if n:match("_head$") or n:match("_skull$") then return {color = {0.7, 0.7, 0.65}, shape = "flower"} end
  local inner = n:match("^infested_(.*)$")
  if inner then return M.definition(inner) end
  inner = n:match("^waxed_(.*)$")
  if inner then return M.definition(inner) end
  if n:match("copper") then return {color = n:match("oxidized") and {0.3, 0.65, 0.55} or {0.75, 0.42, 0.3}} end
  -- Slabs, stairs, fences, walls: the look of their base block.
  local base, kind = n:match("^(.-)_(slab)$")
  if not base then base, kind = n:match("^(.-)_(stairs)$") end
  if not base then base, kind = n:match("^(.-)_(fence)$") end
  if not base then base, kind = n:match("^(.-)_(fence_gate)$") end
  if not base then base, kind = n:match("^(.-)_(wall)$") end
  if not base then base, kind = n:match("^(.-)_(pressure_plate)$") end
  if not base then base, kind = n:match("^(.-)_(button)$") end
  if not base then base, kind = n:match("^(.-)_(trapdoor)$") end
  if not base then base, kind = n:match("^(.-)_(door)$") end
  if not base then base, kind = n:match("^(.-)_(sign)$") end
  if not base then base, kind = n:match("^(.-)_(wall_sign)$") end
  if base then
    local b = D[base] or D[base .. "s"] or D[base .. "_block"] or D[base .. "_planks"]
              or (PLANKS[base] and {color = PLANKS[base]})
              or (base == "petrified_oak" and {color = PLANKS.oak}) or (base == "stone_brick" and D.stone_bricks)
              or (base == "brick" and D.bricks) or (base == "nether_brick" and D.nether_bricks)
              or (base == "cobblestone" and D.cobblestone) or (base == "quartz" and D.quartz_block)
              or (base == "purpur" and D.purpur_block) or (base == "iron" and D.iron_block)
              or family(base)
    if b then
      local shape = ({slab = "slab", stairs = "stairs", fence = "fence", fence_gate = "gate", wall = "wall",
                      pressure_plate = "carpet", button = "carpet", trapdoor = "carpet", door = "door",
                      sign = "torch", wall_sign = "carpet"})[kind]
      local connect = (kind == "wall" and "wall") or (kind == "fence" and (base == "nether_brick" and "nether_fence"
                                                                           or "wood_fence")) or nil
      return {color = b.color or b.side, top = b.top, side = b.side, bottom = b.bottom, mat = b.mat,
              metal = b.metal, roughness = b.roughness, shape = shape, noise = b.noise, connect = connect,
              gate = kind == "fence_gate" or nil}
    end
  end
  return nil
end

-- The definition for a block name (with or without the "minecraft:" prefix); nil when unknown.
function M.definition(name)
  local n = name:gsub("^minecraft:", "")
  local d = D[n]
  if d == nil then
    d = family(n) or false
    D[n] = d
  end
  return d or nil
end

-- ---- pre-1.13 numeric ids -------------------------------------------------------------------------------------
-- legacy[id] = name, or a list indexed by data (+1), or a function(data) -> name[, props]
local WOODS = {"oak", "spruce", "birch", "jungle", "acacia", "dark_oak"}
local function by_data(list, mask)
  return function(d)
    return list[(d & (mask or 15)) + 1] or list[1]
  end
end
local function dyed(suffix) return function(d) return M.DYE_ORDER[(d & 15) + 1] .. suffix end end
local function woods(suffix, offset)
  -- leaves2 has two woods: data 2 and 3 (not written by the game, found in corrupt files) fall back to the first
  return function(d) return (WOODS[(d & 3) + 1 + (offset or 0)] or WOODS[1 + (offset or 0)]) .. suffix end
end
local function slab(list)
  return function(d) return list[(d & 7) + 1] or list[1], {type = d & 8 ~= 0 and "top" or "bottom"} end
end
local STAIR_FACING = {"east", "west", "south", "north"}
local function stairs(name)
  return function(d) return name, {facing = STAIR_FACING[(d & 3) + 1], half = d & 4 ~= 0 and "top" or "bottom"} end
end
local LEGACY = {
  [0] = "air", "stone", "grass_block", "dirt", "cobblestone", "planks", "sapling", "bedrock", "water", "water",
  "lava", "lava", "sand", "gravel", "gold_ore", "iron_ore", "coal_ore", "log", "leaves", "sponge", "glass",
  "lapis_ore", "lapis_block", "dispenser", "sandstone", "note_block", "red_bed", "powered_rail", "detector_rail",
  "sticky_piston", "cobweb", "tallgrass", "dead_bush", "piston", "piston_head", "wool", "moving_piston",
  "dandelion", "poppy", "brown_mushroom", "red_mushroom", "gold_block", "iron_block", "double_stone_slab",
  "stone_slab", "bricks", "tnt", "bookshelf", "mossy_cobblestone", "obsidian", "torch", "fire", "spawner",
  "oak_stairs", "chest", "redstone_wire", "diamond_ore", "diamond_block", "crafting_table", "wheat", "farmland",
  "furnace", "furnace", "oak_sign", "oak_door", "ladder", "rail", "cobblestone_stairs", "oak_wall_sign", "lever",
  "stone_pressure_plate", "iron_door", "oak_pressure_plate", "redstone_ore", "redstone_ore", "redstone_torch",
  "redstone_torch", "stone_button", "snow", "ice", "snow_block", "cactus", "clay", "sugar_cane", "jukebox",
  "oak_fence", "carved_pumpkin", "netherrack", "soul_sand", "glowstone", "nether_portal", "jack_o_lantern", "cake",
  "repeater", "repeater", "stained_glass", "oak_trapdoor", "monster_egg", "stonebrick", "brown_mushroom_block",
  "red_mushroom_block", "iron_bars", "glass_pane", "melon", "pumpkin_stem", "melon_stem", "vine",
  "oak_fence_gate", "brick_stairs", "stone_brick_stairs", "mycelium", "lily_pad", "nether_bricks",
  "nether_brick_fence", "nether_brick_stairs", "nether_wart", "enchanting_table", "brewing_stand", "cauldron",
  "end_portal", "end_portal_frame", "end_stone", "dragon_egg", "redstone_lamp", "redstone_lamp",
  "double_wooden_slab", "wooden_slab", "cocoa", "sandstone_stairs", "emerald_ore", "ender_chest", "tripwire_hook",
  "tripwire", "emerald_block", "spruce_stairs", "birch_stairs", "jungle_stairs", "command_block", "beacon",
  "cobblestone_wall", "flower_pot", "carrots", "potatoes", "oak_button", "skeleton_skull", "anvil",
  "trapped_chest", "light_weighted_pressure_plate", "heavy_weighted_pressure_plate", "comparator", "comparator",
  "daylight_detector", "redstone_block", "nether_quartz_ore", "hopper", "quartz_block", "quartz_stairs",
  "activator_rail", "dropper", "stained_hardened_clay", "stained_glass_pane", "leaves2", "log2", "acacia_stairs",
  "dark_oak_stairs", "slime_block", "barrier", "iron_trapdoor", "prismarine", "sea_lantern", "hay_block", "carpet",
  "terracotta", "coal_block", "packed_ice", "double_plant", "white_banner", "white_wall_banner",
  "daylight_detector", "red_sandstone", "red_sandstone_stairs", "red_sandstone", "red_sandstone_slab",
  "spruce_fence_gate", "birch_fence_gate", "jungle_fence_gate", "dark_oak_fence_gate", "acacia_fence_gate",
  "spruce_fence", "birch_fence", "jungle_fence", "dark_oak_fence", "acacia_fence", "spruce_door", "birch_door",
  "jungle_door", "acacia_door", "dark_oak_door", "end_rod", "chorus_plant", "chorus_flower", "purpur_block",
  "purpur_pillar", "purpur_stairs", "purpur_block", "purpur_slab", "end_stone_bricks", "beetroots", "dirt_path",
  "end_gateway", "repeating_command_block", "chain_command_block", "frosted_ice", "magma_block",
  "nether_wart_block", "red_nether_bricks", "bone_block", "structure_void", "observer",
}
for i, dye in ipairs(M.DYE_ORDER) do
  LEGACY[218 + i] = dye .. "_shulker_box"
  LEGACY[234 + i] = dye .. "_glazed_terracotta"
end
LEGACY[251], LEGACY[252], LEGACY[255] = "concrete", "concrete_powder", "structure_block"
local LEGACY_DATA = {
  stone = by_data({"stone", "granite", "polished_granite", "diorite", "polished_diorite", "andesite",
                   "polished_andesite"}, 7),
  dirt = by_data({"dirt", "coarse_dirt", "podzol"}, 3),
  planks = woods("_planks"), sapling = function(d) return (WOODS[(d & 7) + 1] or "oak") .. "_sapling" end,
  sand = by_data({"sand", "red_sand"}, 1),
  log = function(d) return WOODS[(d & 3) + 1] .. "_log", {axis = ({"y", "x", "z", "y"})[(d >> 2) + 1]} end,
  log2 = function(d) return (WOODS[(d & 3) + 5] or "acacia") .. "_log", {axis = ({"y", "x", "z", "y"})[(d >> 2) + 1]} end, leaves = woods("_leaves"), leaves2 = woods("_leaves", 4),
  tallgrass = by_data({"dead_bush", "grass", "fern", "fern"}, 3),
  wool = dyed("_wool"), carpet = dyed("_carpet"), stained_glass = dyed("_stained_glass"),
  stained_glass_pane = dyed("_stained_glass_pane"), stained_hardened_clay = dyed("_terracotta"),
  concrete = dyed("_concrete"), concrete_powder = dyed("_concrete_powder"),
  poppy = by_data({"poppy", "blue_orchid", "allium", "azure_bluet", "red_tulip", "orange_tulip", "white_tulip",
                   "pink_tulip", "oxeye_daisy"}),
  double_stone_slab = by_data({"smooth_stone", "sandstone", "oak_planks", "cobblestone", "bricks", "stone_bricks",
                               "nether_bricks", "quartz_block"}, 7),
  stone_slab = slab({"smooth_stone_slab", "sandstone_slab", "petrified_oak_slab", "cobblestone_slab", "brick_slab",
                     "stone_brick_slab", "nether_brick_slab", "quartz_slab"}),
  red_sandstone_slab = slab({"red_sandstone_slab"}), purpur_slab = slab({"purpur_slab"}),
  double_wooden_slab = woods("_planks"),
  wooden_slab = function(d) return (WOODS[(d & 7) + 1] or "oak") .. "_slab", {type = d & 8 ~= 0 and "top" or "bottom"} end,
  stonebrick = by_data({"stone_bricks", "mossy_stone_bricks", "cracked_stone_bricks", "chiseled_stone_bricks"}, 3),
  monster_egg = by_data({"infested_stone", "infested_cobblestone", "infested_stone_bricks"}, 3),
  prismarine = by_data({"prismarine", "prismarine_bricks", "dark_prismarine"}, 3),
  sandstone = by_data({"sandstone", "chiseled_sandstone", "cut_sandstone"}, 3),
  red_sandstone = by_data({"red_sandstone", "chiseled_red_sandstone", "cut_red_sandstone"}, 3),
  double_plant = function(d)
    if d & 8 ~= 0 then return "tall_grass" end  -- upper half: the real kind lives in the block below
    return ({"sunflower", "lilac", "tall_grass", "large_fern", "rose_bush", "peony"})[(d & 7) + 1] or "tall_grass"
  end,
  quartz_block = by_data({"quartz_block", "chiseled_quartz_block", "quartz_pillar", "quartz_pillar", "quartz_pillar"}, 7),
  snow = function(d) return "snow", {layers = tostring((d & 7) + 1)} end,
}
for _, s in ipairs({"oak_stairs", "cobblestone_stairs", "brick_stairs", "stone_brick_stairs", "nether_brick_stairs",
                    "sandstone_stairs", "spruce_stairs", "birch_stairs", "jungle_stairs", "quartz_stairs",
                    "acacia_stairs", "dark_oak_stairs", "red_sandstone_stairs", "purpur_stairs"}) do
  LEGACY_DATA[s] = stairs(s)
end

-- Modern name (with "minecraft:") and properties for a pre-1.13 id and data nibble.
function M.legacy_name(id, data)
  local n = LEGACY[id]
  if not n then return ("minecraft:legacy_%d"):format(id) end
  local f = LEGACY_DATA[n]
  local props
  if f then n, props = f(data) end
  return "minecraft:" .. n, props
end

-- ---- materials and shapes -------------------------------------------------------------------------------------
local function linear(c)
  return {c[1] ^ 2.2, c[2] ^ 2.2, c[3] ^ 2.2}
end

local seed_counter = 0
-- A colour texture: the colour modulated by value noise in uv (pixel-sized cells: a 16-texel look).
local function tinted(c, noise, spots)
  local T = torte.texture
  local lc = linear(c)
  seed_counter = seed_counter + 1
  local n = T.value_noise{dims = 2, seed = seed_counter} .. T.uv{scale = 16}
  local amount = noise or 0.3
  local tex = T.constant{value = lc} * ((1 - amount) + 2 * amount * n)
  if spots then
    local s = T.value_noise{dims = 2, seed = seed_counter + 1000} .. T.uv{scale = 6}
    local mask = T.spline{colors = {0, 0, 0, 1, 1}, positions = {0, 0.5, 0.62, 0.7, 1}, interpolation = "linear"} .. s
    tex = tex * (1 - mask) + T.constant{value = linear(spots)} * mask
  end
  return tex
end

local function make_material(d, c)
  local Mt = torte.material
  local lc = linear(c)
  if d.mat == "glass" then return Mt.glass{eta = 1.5, color = {math.sqrt(lc[1]), math.sqrt(lc[2]), math.sqrt(lc[3])}} end
  if d.mat == "water" then return Mt.glass{eta = 1.33, color = lc} end
  if d.mat == "ice" then return Mt.rough_glass{eta = 1.31, roughness = 0.3, color = lc} end
  if d.mat == "metal" then
    if d.metal then return Mt.metal{metal = d.metal, roughness = d.roughness or 0.3} end
    return Mt.metal{metal = "aluminium", roughness = d.roughness or 0.3}
  end
  if d.mat == "plastic" then return Mt.plastic{color = tinted(c, d.noise or 0.15), roughness = 0.3} end
  return Mt.matte{color = tinted(c, d.noise, d.spots)}
end
M.make_material = make_material

-- Cell shapes in the unit cell [0, 1]^3 (a torte.group). `props` are the block-state properties.
local function box(g, lo, hi, m, emission)
  g:add(torte.shape.cube{min = lo, max = hi, material = m, emission = emission})
end
local FACING = {north = {0, -1}, south = {0, 1}, east = {1, 0}, west = {-1, 0}}
-- `emission` (a radiance, or nil): the parts drawn in the block's own material `m` glow (a torch's flame, not
-- its stick); they are meshes, so they become area lights of the grid (voxel cell emitters must be meshes).
local function make_shape(d, props, m, emission)
  local g = torte.group()
  local s = d.shape
  props = props or {}
  local plain_box = box
  local function box(g, lo, hi, mm)
    plain_box(g, lo, hi, mm, mm == m and emission or nil)
  end
  if s == "water" then
    g:add(torte.shape.polygon{points = {{0, 0.875, 0}, {0, 0.875, 1}, {1, 0.875, 1}, {1, 0.875, 0}}, material = m})
  elseif s == "slab_top" then
    box(g, {0, 0.8, 0}, {1, 0.9, 1}, m)
  elseif s == "slab" or s == "slab_low" then
    local h = s == "slab_low" and 0.5625 or 0.5
    if props.type == "top" then box(g, {0, 1 - h, 0}, {1, 1, 1}, m) else box(g, {0, 0, 0}, {1, h, 1}, m) end
  elseif s == "stairs" then
    local top = props.half == "top"
    box(g, {0, top and 0.5 or 0, 0}, {1, top and 1 or 0.5, 1}, m)
    local f = FACING[props.facing or "north"] or FACING.north
    local lo = {f[1] > 0 and 0.5 or 0, top and 0 or 0.5, f[2] > 0 and 0.5 or 0}
    local hi = {f[1] < 0 and 0.5 or 1, top and 0.5 or 1, f[2] < 0 and 0.5 or 1}
    box(g, lo, hi, m)
  elseif s == "layer" then
    local h = (tonumber(props.layers) or 1) / 8
    box(g, {0, 0, 0}, {1, h, 1}, m)
  elseif s == "carpet" then
    box(g, {0, 0, 0}, {1, 0.0625, 1}, m)
  elseif s == "pane" or s == "fence" or s == "wall" then
    -- Connecting blocks: a post and an arm towards each connected side (north -z, south +z, west -x, east +x).
    -- Without connection properties (a caller that gives none) every side is connected.
    local c = M.connections(props)
    if s == "pane" then
      local a, b = 7 / 16, 9 / 16
      box(g, {a, 0, a}, {b, 1, b}, m)
      if c.north then box(g, {a, 0, 0}, {b, 1, a}, m) end
      if c.south then box(g, {a, 0, b}, {b, 1, 1}, m) end
      if c.west then box(g, {0, 0, a}, {a, 1, b}, m) end
      if c.east then box(g, {b, 0, a}, {1, 1, b}, m) end
    elseif s == "fence" then
      local p0, p1, a, b = 6 / 16, 10 / 16, 7 / 16, 9 / 16
      box(g, {p0, 0, p0}, {p1, 1, p1}, m)
      for _, y in ipairs({{6 / 16, 9 / 16}, {12 / 16, 15 / 16}}) do
        if c.north then box(g, {a, y[1], 0}, {b, y[2], p0}, m) end
        if c.south then box(g, {a, y[1], p1}, {b, y[2], 1}, m) end
        if c.west then box(g, {0, y[1], a}, {p0, y[2], b}, m) end
        if c.east then box(g, {p1, y[1], a}, {1, y[2], b}, m) end
      end
    else  -- wall: a post (when `up`) and arms 14/16 high ("low") or full height ("tall")
      local p0, p1, a, b = 4 / 16, 12 / 16, 5 / 16, 11 / 16
      if c.up then box(g, {p0, 0, p0}, {p1, 1, p1}, m) end
      local function h(side) return c[side] == "tall" and 1 or 14 / 16 end
      local lo, hi = c.up and p0 or a, c.up and p1 or b  -- without a post the arms meet in the middle
      if c.north then box(g, {a, 0, 0}, {b, h("north"), c.south and 1 or hi}, m) end
      if c.south then box(g, {a, 0, c.north and 0 or lo}, {b, h("south"), 1}, m) end
      if c.west then box(g, {0, 0, a}, {c.east and 1 or hi, h("west"), b}, m) end
      if c.east then box(g, {c.west and 0 or lo, 0, a}, {1, h("east"), b}, m) end
      if not (c.up or c.north or c.south or c.west or c.east) then box(g, {p0, 0, p0}, {p1, 1, p1}, m) end
    end
  elseif s == "scaffold" then
    box(g, {0.375, 0, 0.375}, {0.625, 1, 0.625}, m)
    box(g, {0, 0.6, 0.4375}, {1, 0.8, 0.5625}, m)
    box(g, {0.4375, 0.6, 0}, {0.5625, 0.8, 1}, m)
  elseif s == "gate" then  -- a closed fence gate across its facing direction
    local f = FACING[props.facing or "north"] or FACING.north
    for _, y in ipairs({{6 / 16, 9 / 16}, {12 / 16, 15 / 16}}) do
      if f[1] == 0 then box(g, {0, y[1], 7 / 16}, {1, y[2], 9 / 16}, m) else box(g, {7 / 16, y[1], 0}, {9 / 16, y[2], 1}, m) end
    end
    if f[1] == 0 then
      box(g, {0, 5 / 16, 7 / 16}, {2 / 16, 1, 9 / 16}, m)
      box(g, {14 / 16, 5 / 16, 7 / 16}, {1, 1, 9 / 16}, m)
    else
      box(g, {7 / 16, 5 / 16, 0}, {9 / 16, 1, 2 / 16}, m)
      box(g, {7 / 16, 5 / 16, 14 / 16}, {9 / 16, 1, 1}, m)
    end
  elseif s == "door" then  -- a closed door: a 3/16 panel on the side it faces away from
    local f = FACING[props.facing or "north"] or FACING.north
    local t = 3 / 16
    if f[2] < 0 then box(g, {0, 0, 1 - t}, {1, 1, 1}, m)
    elseif f[2] > 0 then box(g, {0, 0, 0}, {1, 1, t}, m)
    elseif f[1] < 0 then box(g, {1 - t, 0, 0}, {1, 1, 1}, m)
    else box(g, {0, 0, 0}, {t, 1, 1}, m) end
  elseif s == "torch" then
    box(g, {0.4375, 0, 0.4375}, {0.5625, 0.5, 0.5625}, torte.material.matte{color = linear({0.4, 0.3, 0.18})})
    box(g, {0.42, 0.5, 0.42}, {0.58, 0.66, 0.58}, m)
  elseif s == "flower" then
    box(g, {0.47, 0, 0.47}, {0.53, 0.55, 0.53}, torte.material.matte{color = linear({0.25, 0.5, 0.15})})
    if emission then  -- an emitting head is a small box: analytic shapes cannot emit inside voxel cells
      box(g, {0.39, 0.51, 0.39}, {0.61, 0.73, 0.61}, m)
    else
      g:add(torte.shape.sphere{radius = 0.15, material = m, transform = torte.translate(0.5, 0.62, 0.5)})
    end
  else  -- "cross": two crossed quads
    local h = 0.85
    g:add(torte.shape.polygon{points = {{0.15, 0, 0.15}, {0.85, 0, 0.85}, {0.85, h, 0.85}, {0.15, h, 0.15}},
                              material = m, emission = emission})
    g:add(torte.shape.polygon{points = {{0.85, 0, 0.15}, {0.15, 0, 0.85}, {0.15, h, 0.85}, {0.85, h, 0.15}},
                              material = m, emission = emission})
  end
  return g
end
M.make_shape = make_shape

-- ---- biome tints ---------------------------------------------------------------------------------------------
-- A colour as it looks in a biome class: scaled per channel by the class's grass/foliage/water colour over that of
-- plains (the colours of the definitions are their plains look). Water is tinted half as strongly (square root):
-- its colour is a transmittance, applied once per metre of path.
function M.tint_color(c, kind, class)
  local t, r = biomes.TINTS[class], biomes.TINTS[biomes.REFERENCE]
  if not t or not c then return c end
  local out = {}
  for k = 1, 3 do
    local f = t[kind][k] / r[kind][k]
    if kind == "water" then f = math.sqrt(f) end
    out[k] = math.min(1, c[k] * f)
  end
  return out
end

-- A copy of a tinted definition with its colours for a biome class (grass_block: only the top).
function M.tinted_definition(d, class)
  local out = {}
  for k, v in pairs(d) do out[k] = v end
  if d.top then
    out.top = M.tint_color(d.top, d.tint, class)
  else
    out.color = M.tint_color(d.color, d.tint, class)
  end
  return out
end

-- ---- the registry ---------------------------------------------------------------------------------------------
local Registry = {}
Registry.__index = Registry

-- Properties that change a block's shape (everything else shares one voxel id).
local SHAPE_PROPS = {slab = {"type"}, slab_low = {}, stairs = {"facing", "half"}, layer = {"layers"},
                     pane = {"north", "east", "south", "west"}, fence = {"north", "east", "south", "west"},
                     wall = {"north", "east", "south", "west", "up"}, gate = {"facing"}, door = {"facing"}}
local SIDES = {"north", "east", "south", "west"}

-- The connections of a fence, wall or pane from its block-state properties: {north = false | true | "low" |
-- "tall", ..., up = bool}. 1.13+ states say "true"/"false" (walls from 1.16: "none"/"low"/"tall"). No properties
-- at all (nil) means connected on every side.
function M.connections(props)
  local c = {}
  local any = false
  for _, k in ipairs(SIDES) do
    local v = props and props[k]
    if v ~= nil then any = true end
    if v == "true" or v == true or v == "low" then c[k] = "low"
    elseif v == "tall" then c[k] = "tall"
    else c[k] = false end
  end
  if not any then
    for _, k in ipairs(SIDES) do c[k] = "low" end
  end
  local up = props and props.up
  if up == nil then c.up = not any or not ((c.north and c.south and not c.east and not c.west)
                                          or (c.east and c.west and not c.north and not c.south))
  else c.up = up == "true" or up == true end
  return c
end

function M.registry()
  return setmetatable({
    by_key = {},       -- "name[props]" -> voxel id
    entries = {},      -- voxel id -> {key, name, def, props}
    next_cube = 1, next_cell = -1,
    unknown = {},      -- name -> blocks drawn with the fallback look
    unknown_blocks = 0,
    legacy_cache = {},
    tint_kind = {},    -- id -> "grass" | "foliage" | "water" for blocks whose colour follows the biome
    tint_cache = {},   -- id -> {class -> tinted variant id}
    family = {},       -- id -> connection family of fences, walls, panes ("gate" for fence gates)
    solid_cache = {},
  }, Registry)
end

-- Voxel id for a block state (name with namespace, props a table or nil). Air and invisible blocks give 0.
function Registry:state(name, props)
  if M.AIR[name] then return 0 end
  local d = M.definition(name)
  local key = name
  if d and d.shape and props then
    if d.connect then  -- one key per connection shape: "true" and "low" (walls before/after 1.16) are the same
      if props.north ~= nil or props.east ~= nil or props.south ~= nil or props.west ~= nil then
        local c = M.connections(props)
        local code = ""
        for _, k in ipairs(SIDES) do code = code .. (c[k] == "tall" and "2" or c[k] and "1" or "0") end
        if d.shape == "wall" then code = code .. (c.up and "u" or "") end
        key = key .. ",c=" .. code
      end
    else
      local keys = SHAPE_PROPS[d.shape]
      if keys then
        for _, k in ipairs(keys) do
          if props[k] ~= nil then key = key .. "," .. k .. "=" .. tostring(props[k]) end
        end
      end
    end
  end
  if d and d.pillar and props and (props.axis == "x" or props.axis == "z") then key = key .. ",axis=" .. props.axis end
  if not d then key = "?" .. name end
  local id = self.by_key[key]
  if id then return id end
  if d and d.invisible then
    id = 0
  else
    id = self:new_id(d and d.shape)
  end
  self.by_key[key] = id
  if id ~= 0 then
    self.entries[id] = {key = key, name = name, def = d, props = props, known = d ~= nil}
    if d and d.tint then self.tint_kind[id] = d.tint end
    if d and (d.connect or d.gate) then self.family[id] = d.connect or "gate" end
  end
  return id
end

-- A fresh voxel id: a cell shape (< 0) or a cube (> 0).
function Registry:new_id(cell)
  local id
  if cell then
    id = self.next_cell
    self.next_cell = id - 1
  else
    id = self.next_cube
    self.next_cube = id + 1
  end
  if id < -32768 or id > 32767 then error("too many distinct block states for 16-bit voxel ids", 0) end
  return id
end

-- The variant of a biome-tinted id (self.tint_kind[id] ~= nil) for a tint class of minecraft.biomes: an extra
-- voxel id, made on first use, one per (block state, class).
function Registry:tinted(id, class)
  local t = self.tint_cache[id]
  if not t then
    t = {}
    self.tint_cache[id] = t
  end
  local v = t[class]
  if v then return v end
  local e = self.entries[id]
  if not e or not self.tint_kind[id] then return id end
  local key = e.key .. "@" .. class
  v = self.by_key[key]
  if not v then
    v = self:new_id(id < 0)
    self.by_key[key] = v
    self.entries[v] = {key = key, name = e.name, def = e.def, props = e.props, known = e.known, tint = class, base = id}
  end
  t[class] = v
  return v
end

-- The tint class of an id (nil when untinted).
function Registry:tint(id)
  local e = self.entries[id]
  return e and e.tint
end

-- Blocks that are full cubes but that fences, walls and panes do not attach to (Minecraft's exceptions).
local NO_ATTACH = {}
for n in ([[glowstone sea_lantern pumpkin carved_pumpkin jack_o_lantern melon beacon barrier ice packed_ice
            blue_ice frosted_ice glass tinted_glass]]):gmatch("%S+") do NO_ATTACH["minecraft:" .. n] = true end

-- Whether a fence, wall or pane next to this id attaches to it: solid cubes (not glass, ice, leaves, lamps).
function Registry:solid(id)
  if id <= 0 then return false end
  local v = self.solid_cache[id]
  if v ~= nil then return v end
  local e = self.entries[id]
  local d = e and e.def
  v = e ~= nil and not NO_ATTACH[e.name] and not (d and (d.mat == "glass" or d.mat == "leaves" or d.mat == "ice"
                                                         or d.mat == "water" or e.name:find("shulker_box")))
  self.solid_cache[id] = v
  return v
end

-- The id of the same block as `id` with the connections `c` ({north = bool | "low" | "tall", ..., up = bool}).
function Registry:connected(id, c)
  local e = self.entries[id]
  local props = {}
  if e.props then for k, v in pairs(e.props) do props[k] = v end end
  local wall = e.def and e.def.shape == "wall"
  for _, k in ipairs(SIDES) do
    local v = c[k]
    props[k] = wall and (v == "tall" and "tall" or v and "low" or "none") or (v and "true" or "false")
  end
  if wall then props.up = c.up and "true" or "false" end
  return self:state(e.name, props)
end

function Registry:legacy(id, data)
  local k = id * 16 + data
  local v = self.legacy_cache[k]
  if v then return v end
  local name, props = M.legacy_name(id, data)
  v = self:state(name, props)
  self.legacy_cache[k] = v
  return v
end

-- Counts blocks drawn with the fallback look (called by the loader with per-id block counts).
function Registry:count_unknown(id, n)
  local e = self.entries[id]
  if e and not e.known then
    self.unknown[e.name] = (self.unknown[e.name] or 0) + n
    self.unknown_blocks = self.unknown_blocks + n
  end
end

-- Emission of an id (a colour) or nil.
function Registry:emission(id)
  local e = self.entries[id]
  return e and e.def and e.def.emit
end

-- Every id handed out for a block name (all its states and biome variants), as a set {[id] = true}.
function Registry:ids_of(name)
  if not name:find(":", 1, true) then name = "minecraft:" .. name end
  local out = {}
  for id, e in pairs(self.entries) do
    if e.name == name then out[id] = true end
  end
  return out
end

function Registry:name(id)
  local e = self.entries[id]
  return e and e.name
end

-- Calls grid:define{...} for every id handed out. Emitting blocks (`emit` in their definition: glowstone, lava,
-- torches, fire, ...) light the scene: their exposed faces, or the glowing parts of their cell shapes, become
-- the grid's area lights. `options.emission = false` draws them unlit (their look only).
function Registry:define(grid, options)
  local glow = not (options and options.emission == false)
  local ids = {}
  for id in pairs(self.entries) do ids[#ids + 1] = id end
  table.sort(ids)
  local materials = {}
  local function mat(d, c)
    local k = tostring(d) .. ":" .. table.concat(c, ",")
    materials[k] = materials[k] or make_material(d, c)
    return materials[k]
  end
  local tinted_defs = {}
  for _, id in ipairs(ids) do
    local e = self.entries[id]
    local d = e.def or {color = M.FALLBACK_COLOR, noise = 0}
    if e.tint and d.tint then  -- a biome variant: the same definition with its colour (or top) tinted
      local k = tostring(d) .. "@" .. e.tint
      if not tinted_defs[k] then tinted_defs[k] = M.tinted_definition(d, e.tint) end
      d = tinted_defs[k]
    end
    local emission = glow and d.emit or nil
    if id > 0 then
      local axis = d.pillar and e.props and e.props.axis
      if (d.top or d.side or d.bottom) and (axis == "x" or axis == "z") then
        -- A log lying along x or z: its end faces point along that axis.
        local side, top, bottom = mat(d, d.side or d.color), mat(d, d.top or d.side), mat(d, d.bottom or d.side)
        local f = {["+y"] = side, ["-y"] = side, ["+x"] = side, ["-x"] = side, ["+z"] = side, ["-z"] = side}
        f["+" .. axis], f["-" .. axis] = top, bottom
        grid:define{id = id, faces = f, emission = emission}
      elseif d.top or d.side or d.bottom then
        local side = d.side or d.color
        grid:define{id = id, faces = {top = mat(d, d.top or side), bottom = mat(d, d.bottom or side),
                                      side = mat(d, side)}, emission = emission}
      else
        grid:define{id = id, material = mat(d, d.color), emission = emission}
      end
    else
      grid:define{id = id, shape = make_shape(d, e.props, mat(d, d.color or d.side), emission)}
    end
  end
end

return M
