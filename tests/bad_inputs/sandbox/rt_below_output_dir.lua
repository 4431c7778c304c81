-- expect: may not be written under --sandbox
-- flags: --sandbox
-- args: output=$TMP/results/image.exr
-- The directory of output= is writable, not the directories below it.
io.open(torte.args.output:match("^(.*)/") .. "/sub/other.txt", "w")
