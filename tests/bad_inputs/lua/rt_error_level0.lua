-- expect: no position given
-- error(msg, 0) carries no location: the script's line is added.
error("no position given", 0)
