-- expect: torte.light.environment: '/etc/passwd' may not be read
-- flags: --sandbox
torte.light.environment{file = "/etc/passwd"}
