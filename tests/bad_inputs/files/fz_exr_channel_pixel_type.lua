-- expect: cannot read image texture 'pixel-type.exr': corrupt OpenEXR header: attribute 'channels': channel 'G' has pixel type 240766 (0 uint, 1 half, 2 float)
-- OpenImageIO 2.4 aborts the whole process on a channel pixel type it does not know; found by fuzz/fuzz_image.cc.
local function attr(name, kind, value) return name .. "\0" .. kind .. "\0" .. string.pack("<i4", #value) .. value end
local function channel(name, type) return name .. "\0" .. string.pack("<i4i4i4i4", type, 0, 1, 1) end
local f = assert(io.open("pixel-type.exr", "wb"))
f:write("\x76\x2f\x31\x01\x02\0\0\0" ..
        attr("channels", "chlist", channel("B", 1) .. channel("G", 240766) .. channel("R", 1) .. "\0") ..
        attr("compression", "compression", "\3") ..
        attr("dataWindow", "box2i", string.pack("<i4i4i4i4", 0, 0, 7, 7)) ..
        attr("displayWindow", "box2i", string.pack("<i4i4i4i4", 0, 0, 7, 7)) ..
        attr("lineOrder", "lineOrder", "\0") .. attr("pixelAspectRatio", "float", string.pack("<f", 1)) ..
        attr("screenWindowCenter", "v2f", string.pack("<ff", 0, 0)) ..
        attr("screenWindowWidth", "float", string.pack("<f", 1)) .. "\0" .. string.rep("\0", 64))
f:close()
torte.texture.image{file = "pixel-type.exr"}
