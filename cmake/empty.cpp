// keeps object libraries non-empty while a layer has no sources yet
