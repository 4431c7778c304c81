-- expect: cannot read image texture 'huge-attribute.exr': corrupt OpenEXR header: attribute 'comments' (string) claims 2147483647 bytes
-- OpenEXR 3.1 allocates a string attribute's declared size before reading it: 2 GB for this 30-byte file;
-- found by fuzz/fuzz_image.cc.
local f = assert(io.open("huge-attribute.exr", "wb"))
f:write("\x76\x2f\x31\x01" .. string.pack("<I4", 2) .. "comments\0string\0" .. string.pack("<i4", 0x7fffffff) .. "abc")
f:close()
torte.texture.image{file = "huge-attribute.exr"}
