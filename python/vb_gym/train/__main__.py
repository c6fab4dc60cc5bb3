from .ppo import main

main()
