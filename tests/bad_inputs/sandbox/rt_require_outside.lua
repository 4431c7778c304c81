-- expect: require: '/etc/passwd' may not be read
-- flags: --sandbox
-- The file require finds obeys the policy too.
package.path = "/etc/?"
require "passwd"
