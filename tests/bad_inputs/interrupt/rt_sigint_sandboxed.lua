-- expect: -
-- sigint: 3
-- timeout: 10
-- flags: --sandbox
while true do end
