-- expect: cannot read image texture 'runs-on.exr': corrupt OpenEXR header: attribute 'channels': the channel list does not end where its size says
-- OpenEXR reads a channel list up to its empty name, not by the attribute's size: here the last entry runs past
-- the 33 declared bytes, OpenEXR then reads the later attributes at other offsets than the size says and finds a
-- 13.6 M-pixel ZIP data window, for which it allocated 1.3 GB line buffers three times; found by fuzz/fuzz_image.cc.
local function attr(name, kind, value) return name .. "\0" .. kind .. "\0" .. string.pack("<i4", #value) .. value end
local function channel(name) return name .. "\0" .. string.pack("<i4i4i4i4", 1, 0, 1, 1) end
local f = assert(io.open("runs-on.exr", "wb"))
f:write("\x76\x2f\x31\x01\x02\0\0\0" ..
        attr("channels", "chlist", (channel("G") .. channel("R")):sub(1, 33)) ..
        "\0" .. attr("compression", "compression", "\3") ..
        attr("dataWindow", "box2i", string.pack("<i4i4i4i4", -13631744, -1, -1, -1)) .. "\0")
f:close()
torte.texture.image{file = "runs-on.exr"}
