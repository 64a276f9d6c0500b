local slender = require("slender")
slender.plugin(slender.var("plugin", "libold_abi.so"))
