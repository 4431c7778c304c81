-- Lua-side part of the torte module, run at start-up before the scene script.
local torte = require "torte"

local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = tostring(k) end
  table.sort(keys)
  return keys
end

-- The script's command-line arguments (key=value) merged over `defaults`. An argument the scene does not
-- declare, or one of the wrong type, is an error at the caller's line.
function torte.options(defaults)
  local list = rawget(torte, "_list_args")  -- torte --list-args: print the arguments and stop the script here
  if list then list(defaults) end
  local out = {}
  for k, v in pairs(defaults) do out[k] = v end
  -- In key order, so that of several bad arguments the same one is reported on every run.
  local names = {}
  for k in pairs(torte.args) do names[#names + 1] = k end
  table.sort(names, function(a, b) return tostring(a) < tostring(b) end)
  for _, k in ipairs(names) do
    local v = torte.args[k]
    local default = defaults[k]
    if default == nil then
      error(("unknown argument '%s' (this scene accepts: %s)"):format(k, table.concat(sorted_keys(defaults), ", ")), 2)
    end
    if type(default) == "number" and type(v) ~= "number" then
      error(("argument '%s' must be a number, got '%s'"):format(k, tostring(v)), 2)
    elseif type(default) == "boolean" and type(v) ~= "boolean" then
      error(("argument '%s' must be true or false, got '%s'"):format(k, tostring(v)), 2)
    elseif type(default) == "string" then
      v = tostring(v)
    end
    out[k] = v
  end
  return out
end

-- Writes the image to `path` (the extension picks the format). High-dynamic-range outputs (.exr, .hdr) get a
-- PNG preview beside them with the same name.
function torte.save(image, path, options)
  local ok, err = pcall(function()
    image:write(path, options)
    local stem, ext = path:match("^(.*)%.(%w+)$")
    if ext and (ext:lower() == "exr" or ext:lower() == "hdr") then
      image:write(stem .. ".png", options)
    end
  end)
  if not ok then
    -- Report the error at the script line that called torte.save, not inside this library.
    error(tostring(err):gsub("^%[torte%][^:]*:%d+: ", ""), 2)
  end
  return image
end

return torte
