-- expect: torte.mesh.load: '/etc/passwd' may not be read
-- flags: --sandbox
torte.mesh.load("/etc/passwd")
