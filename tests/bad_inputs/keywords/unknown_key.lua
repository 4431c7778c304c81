-- expect: unknown key 'radis'
torte.shape.sphere{radis = 1}
