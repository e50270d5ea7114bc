"""Node-group builders only: one module per group (NAME, VERSION, TREE_TYPE, DESCRIPTION,
build(tree)), helper.py for versioned groups, sockets and the left-to-right layout, and
catalog.py, the table of every group that the Add menus and the snapshot tests read."""
