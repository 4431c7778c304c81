-- expect: image texture 'wide.bmp' (19791880x8, 3 channels) needs ~
-- flags: --max-memory 1GB
-- A 19791880x8 BMP texture (a 300-byte file) passed the size check, which counted 4 bytes per texel, and
-- OpenImageIO's cache then took 2 GB reading it as one tile; found by fuzz/fuzz_image.cc.
local header = "BM" .. string.pack("<I4I2I2I4", 246, 0, 0, 54) ..
               string.pack("<I4i4i4I2I2I4I4i4i4I4I4", 40, 19791880, 8, 1, 24, 0, 64, 0, 0, 0, 0)
local f = assert(io.open("wide.bmp", "wb"))
f:write(header .. ("\255"):rep(192))
f:close()
torte.texture.image{file = "wide.bmp"}
