-- expect: debug.setlocal: Lua's internal slots cannot be set
-- Local 1 here is the numeric for loop's internal state, which the VM does not check again.
for i = 1, 2 do debug.setlocal(1, 1, {}) end
