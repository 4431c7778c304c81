-- expect: torte.scene: 'memory_budget' must be a size such as "1.5GB" or a number of bytes, got boolean
torte.scene{memory_budget = true}
