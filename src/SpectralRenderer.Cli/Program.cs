using SpectralRenderer.Cli;

Signals.AnswerUntilExit();   // a signal after the command returned must not turn its exit code into 130 or 143
return CommandLine.Run(args, Console.Out, Console.Error);
