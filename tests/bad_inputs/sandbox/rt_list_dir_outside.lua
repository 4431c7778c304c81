-- expect: torte.data.list_dir: '/' may not be read
-- flags: --sandbox
torte.data.list_dir("/")
