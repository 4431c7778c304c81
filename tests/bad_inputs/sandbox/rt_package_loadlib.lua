-- expect: attempt to call a nil value (field 'loadlib')
-- flags: --sandbox
package.loadlib("libc.so.6", "*")
