-- expect: 'radius' must be a number, got string
torte.shape.sphere{radius = "one"}
