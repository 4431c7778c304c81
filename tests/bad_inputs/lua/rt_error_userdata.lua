-- expect: (error object is a torte.scene value)
error(torte.scene())
