-- expect: torte.texture.image: '/etc/passwd' may not be read
-- flags: --sandbox
torte.texture.image{file = "/etc/passwd"}
