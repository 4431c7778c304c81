-- expect: unknown option '--sppp'
-- args: --sppp=4
-- where: see 'torte --help'
-- Options may follow the script (CLI11): a misspelled one there is a usage error too, before the script runs.
error('the script ran')
