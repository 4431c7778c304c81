-- expect: cannot read image texture 'huge-chunk.png': corrupt PNG file: chunk 'tEXt' claims 2113929242 bytes
-- libpng 1.6 (Debian's, no chunk allocation limit) allocates an ancillary chunk's declared length before reading
-- it: 2 GB for this 60-byte file; found by fuzz/fuzz_image.cc.
local function chunk(kind, data)
  return string.pack(">I4", #data) .. kind .. data .. "\0\0\0\0"  -- CRCs are not checked before the length
end
local f = assert(io.open("huge-chunk.png", "wb"))
f:write("\x89PNG\r\n\x1a\n" .. chunk("IHDR", string.pack(">I4I4BBBBB", 6, 5, 8, 0, 0, 0, 0)) ..
        string.pack(">I4", 2113929242) .. "tEXtComment\0only a few bytes")
f:close()
torte.texture.image{file = "huge-chunk.png"}
