-- expect: -
-- sigint: 3
-- timeout: 10
-- Most of the time goes to C functions of the string library; the hook stops the script between them.
local parts = {}
while true do parts[#parts % 1000 + 1] = string.rep("x", 1000):upper() end
