-- expect: torte.shape.mesh: '/etc/passwd' may not be read
-- flags: --sandbox
torte.shape.mesh{file = "/etc/passwd"}
